/**
 * The History panel shows the arm's current profile's servos only: series, tracking rows and
 * alarms of servos stored under the same arm id by an earlier profile are left out and named.
 */
import { describe, expect, test } from 'vitest';
import type { OverviewViews } from '../src/ui/panels/History/loadHistory.ts';
import { onlyProfileServos } from '../src/ui/panels/History/profileServos.ts';

const echo = { arm: 'arm1', start: 0, stop: 1000 };
const series = (id: string) => ({ id, times: [0], values: [30] });

function overview(ids: string[]): OverviewViews {
  return {
    range: { start: 0, stop: 1000 },
    temp: {
      ok: true,
      data: { ...echo, field: 'temp', every: '1s', everyMs: 1000, series: ids.map(series) },
    },
    volt: { ok: false, error: 'HTTP 503' },
    thermal: { ok: false, error: 'HTTP 503' },
    tracking: {
      ok: true,
      data: {
        ...echo,
        unit: 'deg',
        thinnedEveryMs: null,
        truncated: false,
        joints: ids.map((id) => ({ id, samples: 1, meanAbsError: 0, maxAbsError: 0, maxAt: 0 })),
      },
    },
    alarms: {
      ok: true,
      data: {
        ...echo,
        truncated: false,
        episodes: ids.map((id) => ({ kind: 'temp-warning', arm: 'arm1', id, start: 0 })),
      },
    },
  } as OverviewViews;
}

describe('onlyProfileServos', () => {
  test('servos 006 and 007 of an earlier 7-axis profile are left out of every view and named', () => {
    const six = ['000', '001', '002', '003', '004', '005'];
    const r = onlyProfileServos(overview([...six, '007', '006']), six);
    expect(r.others).toEqual(['006', '007']);
    const t = r.overview.temp;
    expect(t.ok && t.data.series.map((s) => s.id)).toEqual(six);
    const k = r.overview.tracking;
    expect(k.ok && k.data.joints.map((j) => j.id)).toEqual(six);
    const a = r.overview.alarms;
    expect(a.ok && a.data.episodes.map((e) => e.id)).toEqual(six);
    expect(r.overview.volt).toEqual({ ok: false, error: 'HTTP 503' }); // a failed view stays failed
  });

  test('nothing to leave out: the same views, no others', () => {
    const ids = ['000', '001'];
    const o = overview(ids);
    const r = onlyProfileServos(o, ids);
    expect(r.others).toEqual([]);
    expect(r.overview).toEqual(o);
  });
});
