/** A default run's table keeps the soak's rows from the newest run that measured it. */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { markdown, newestRunOf, type RunRecord } from '../lib/report.ts';
import type { Section } from '../lib/types.ts';

const section = (id: string, title: string): Section => ({
  id,
  title,
  run: async () => ({ rows: [], settings: {}, data: {} }),
});

function run(stamp: string, sections: RunRecord['sections']): RunRecord {
  return {
    stamp,
    startedAt: stamp,
    finishedAt: stamp,
    mode: 'full',
    command: 'npm run bench',
    machine: { cores: 2, cpuModel: 'x', memoryGiB: 1, loadAverageAtStart: [0, 0, 0] },
    versions: {},
    sections,
  };
}

const soakOk = (slope: string) => ({
  status: 'ok' as const,
  durationS: 1,
  title: 'Soak',
  settings: {},
  data: {},
  rows: [{ figure: 'Heap slope', value: slope, baseline: '', target: '< 1', met: true }],
});

describe('carried sections (bench/lib/report.ts)', () => {
  it('finds the newest run where the section was measured, skipping failed ones and other files', () => {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'bench-carry-'));
    const put = (r: RunRecord) =>
      fs.writeFileSync(path.join(dir, `${r.stamp}.json`), JSON.stringify(r));
    put(run('2026-01-01T00-00-00', { soak: soakOk('0.5') }));
    put(run('2026-01-02T00-00-00', { soak: soakOk('0.1') }));
    put(
      run('2026-01-03T00-00-00', {
        soak: { status: 'failed', reason: 'x', durationS: 0, title: 'Soak' },
      }),
    );
    put(run('2026-01-04T00-00-00', {}));
    fs.writeFileSync(path.join(dir, '2026-01-05T00-00-00-plot.svg'), '<svg/>');
    const c = newestRunOf(dir, 'soak');
    expect(c?.stamp).toBe('2026-01-02T00-00-00');
    expect(newestRunOf(dir, 'nothing')).toBeNull();
    expect(newestRunOf(path.join(dir, 'missing'), 'soak')).toBeNull();

    const now = run('2026-01-06T00-00-00', {
      ik: {
        status: 'ok',
        durationS: 1,
        title: 'IK',
        settings: {},
        data: {},
        rows: [{ figure: 'IK', value: '1', baseline: '', target: '', met: null }],
      },
    });
    const md = markdown(now, [section('ik', 'IK'), section('soak', 'Soak')], 'x.json', {
      soak: c!,
    });
    expect(md).toContain('| 1 | IK | 1 |');
    expect(md).toContain('| 2 | Heap slope (run `2026-01-02T00-00-00`) | 0.1 |');
  });
});
