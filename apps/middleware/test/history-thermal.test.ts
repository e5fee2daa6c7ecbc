/**
 * `/history/thermal-model` with a fake reader answering windowed means, as InfluxDB would, of a
 * servo that follows a known model: the endpoint recovers its parameters; the grid is coarser
 * for a longer range; a bad parameter is refused before anything is queried.
 */
import { describe, expect, test } from 'vitest';
import { stepTemperature, type ThermalParams } from '@armtwin/thermal';
import { DEFAULT_HISTORY_OPTIONS } from '../src/history/options.ts';
import { parseParams, type HistoryParams } from '../src/history/params.ts';
import type { HistoryReader } from '../src/history/reader.ts';
import type { Row } from '../src/history/shape.ts';
import { thermalModel, thermalStep } from '../src/history/thermal.ts';

const T0 = Date.UTC(2024, 0, 1);
const TRUE: ThermalParams = {
  tauS: 25,
  restC: 32,
  gainCPerDegS: 0.08,
  volt0V: 7.2,
  sagVPerDegS: 0.001,
};
const SECONDS = 600;

/** 10 ms truth: the servo sweeps ±45° at 150 deg/s for 30 s, rests 30 s, and so on. */
function truth() {
  const temp: { t: number; v: number }[] = [];
  const angle: { t: number; v: number }[] = [];
  let T = TRUE.restC;
  let a = 0;
  let dir = 1;
  for (let ms = 0; ms < SECONDS * 1000; ms += 10) {
    const moving = Math.floor(ms / 30_000) % 2 === 0;
    const v = moving ? 150 : 0;
    a += dir * v * 0.01;
    if (Math.abs(a) >= 45) dir = -dir;
    T = stepTemperature(TRUE, T, v, 0.01);
    if (ms % 500 === 0) temp.push({ t: T0 + ms, v: Math.round(T) });
    if (ms % 20 === 0) angle.push({ t: T0 + ms, v: a });
  }
  return { temp, angle };
}

/** Mean per epoch-aligned window, stamped at the window's start, as `series` answers. */
function windowed(samples: { t: number; v: number }[], everyMs: number, id: string): Row[] {
  const by = new Map<number, number[]>();
  for (const s of samples) {
    const w = Math.floor(s.t / everyMs) * everyMs;
    if (!by.has(w)) by.set(w, []);
    by.get(w)!.push(s.v);
  }
  return [...by].map(([w, vs]) => ({
    _time: new Date(w).toISOString(),
    _value: vs.reduce((x, y) => x + y, 0) / vs.length,
    id,
  }));
}

const ms = (every: string) =>
  every.endsWith('ms') ? Number(every.slice(0, -2)) : Number(every.slice(0, -1)) * 1000;

function fakeReader(asked: string[]): HistoryReader {
  const { temp, angle } = truth();
  const volt = temp.map((s) => ({ t: s.t, v: TRUE.volt0V }));
  return {
    language: 'influxql',
    series: async (p: HistoryParams, every: string) => {
      asked.push(`${p.field}@${every}`);
      const src = p.field === 'temp' ? temp : p.field === 'volt' ? volt : angle;
      return windowed(src, ms(every), '001');
    },
  } as unknown as HistoryReader;
}

describe('/history/thermal-model', () => {
  test('recovers the servo model from windowed means on a 1 s grid (angles at 20 ms)', async () => {
    const asked: string[] = [];
    const p: HistoryParams = {
      arm: 'arm1',
      ids: 'all',
      field: 'angle',
      startMs: T0,
      stopMs: T0 + SECONDS * 1000,
    };
    const answer = await thermalModel(
      { reader: fakeReader(asked), options: DEFAULT_HISTORY_OPTIONS },
      p,
    );
    expect(asked.sort()).toEqual(['angle@20ms', 'temp@20ms', 'volt@1s']);
    expect(answer.stepMs).toBe(1000);
    expect(answer.servos).toHaveLength(1);
    const s = answer.servos[0]!;
    expect(s).toMatchObject({ id: '001', fitted: true, tauFitted: true, reason: '' });
    expect(Math.abs(s.params.tauS - TRUE.tauS) / TRUE.tauS).toBeLessThan(0.1);
    expect(Math.abs(s.params.restC - TRUE.restC)).toBeLessThan(0.7);
    expect(Math.abs(s.params.gainCPerDegS - TRUE.gainCPerDegS) / TRUE.gainCPerDegS).toBeLessThan(
      0.1,
    );
    expect(s.params.volt0V).toBeCloseTo(TRUE.volt0V, 6);
    expect(s.rmseC).toBeLessThan(1);
    expect(JSON.parse(JSON.stringify(answer))).toEqual(answer); // no NaN in the JSON

    // The model's temperature from the motion alone, beside the measured one (History charts).
    expect(answer.times).toHaveLength(SECONDS);
    expect(answer.times[0]).toBe(T0 + 500);
    const { temp, volt } = s.predicted;
    expect(temp).toHaveLength(SECONDS);
    const measured = truth().temp;
    let worst = 0;
    answer.times.forEach((t, k) => {
      const m = measured.find((x) => x.t >= t);
      if (m && temp[k] !== null) worst = Math.max(worst, Math.abs(temp[k]! - m.v));
    });
    expect(worst).toBeLessThan(2); // within the reports' 1 °C rounding and the fit's error
    expect(temp.filter((x) => x === null).length).toBeLessThan(3);
    expect(volt.every((v) => v === null || Math.abs(v - TRUE.volt0V) < 0.05)).toBe(true);
    // A supply that never sags: the motion drew no power, measured or predicted.
    expect(answer.power.measuredW.every((w) => w === null || w < 0.05)).toBe(true);
    expect(answer.power.supplyOhms).toBe(DEFAULT_HISTORY_OPTIONS.thermalSupplyOhms);
  });

  test('a longer range gets a coarser grid, within the cell bound', () => {
    expect(thermalStep(T0, T0 + 3_600_000, 1000, 7200).ms).toBe(1000);
    expect(thermalStep(T0, T0 + 24 * 3_600_000, 1000, 7200).ms).toBe(15_000);
  });

  test('takes arm, id, start and stop only', () => {
    const q = (s: string) => parseParams('thermal-model', new URLSearchParams(s), T0, 1e12);
    expect(q('arm=arm1&start=-1h&id=001')).toMatchObject({ ok: true });
    expect(q('arm=arm1&field=temp')).toMatchObject({ ok: false, parameter: 'field' });
  });
});
