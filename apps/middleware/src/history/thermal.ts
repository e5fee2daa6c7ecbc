/**
 * `/history/thermal-model`: each servo's thermal and electrical model (@armtwin/protocol's
 * thermal-model.ts) fitted from its history in range. Asks the reader for the windowed means of
 * `volt` on a grid of `stepMs`, and of `temp` and `angle` in windows as fine as
 * `thermalMaxAngleCells` allows: each report's own time for the temperature (thermal-trace.ts
 * takes it at the grid's centres), the path each servo travelled for the motion (coarser windows
 * average away quick reversals and make the arm look slower than it was). Then fits by least
 * squares (thermal-fit.ts). Only the reader does I/O.
 */
import type { ThermalModelAnswer, ThermalServoFit } from '@armtwin/api';
import {
  armPowerW,
  fitThermal,
  predictTrace,
  thermalTraces,
  type ServoSamples,
  type TimedValue,
} from '@armtwin/thermal';
import type { EndpointContext } from './endpoints.ts';
import type { HistoryParams } from './params.ts';
import { samplesBy } from './shape.ts';
import { WINDOW_LADDER, windowCount } from './window.ts';

const finite = (x: number): number | null => (Number.isFinite(x) ? x : null);
/** A predicted value as JSON: null where unknown, else to 0.01 (°C, V, W). */
const value = (x: number): number | null => (Number.isFinite(x) ? Math.round(x * 100) / 100 : null);

/** The grid: the smallest ladder step of at least `minMs` giving ≤ maxCells cells. */
export function thermalStep(
  startMs: number,
  stopMs: number,
  minMs: number,
  maxCells: number,
): { ms: number; text: string } {
  for (const w of WINDOW_LADDER)
    if (w.ms >= minMs && windowCount(startMs, stopMs, w.ms) <= maxCells) return w;
  return WINDOW_LADDER[WINDOW_LADDER.length - 1]!;
}

/** The angle windows: the finest ladder step of at least `minMs` within `maxCells`, ≤ `stepMs`. */
export function angleStep(
  startMs: number,
  stopMs: number,
  minMs: number,
  maxCells: number,
  stepMs: number,
): { ms: number; text: string } {
  let best = WINDOW_LADDER[0]!;
  for (const w of WINDOW_LADDER) {
    if (w.ms > stepMs) break;
    best = w;
    if (w.ms >= minMs && windowCount(startMs, stopMs, w.ms) <= maxCells) return w;
  }
  return best;
}

export async function thermalModel(
  ctx: EndpointContext,
  p: HistoryParams,
): Promise<ThermalModelAnswer> {
  const o = ctx.options;
  const step = thermalStep(p.startMs, p.stopMs, o.thermalMinStepMs, o.thermalMaxCells);
  const fine = angleStep(p.startMs, p.stopMs, o.thermalMinAngleMs, o.thermalMaxAngleCells, step.ms);
  const [temp, volt, angle] = await Promise.all([
    ctx.reader.series({ ...p, field: 'temp' }, fine.text),
    ctx.reader.series({ ...p, field: 'volt' }, step.text),
    ctx.reader.series({ ...p, field: 'angle' }, fine.text),
  ]);
  const byTemp = samplesBy(temp);
  const byVolt = samplesBy(volt);
  const byAngle = samplesBy(angle);
  const ids = [...new Set([...byTemp.keys(), ...byAngle.keys()])].sort();
  const none: TimedValue[] = [];
  // A fine window's mean belongs to its middle.
  const mid = (list: readonly TimedValue[]) => list.map((s) => ({ t: s.t + fine.ms / 2, v: s.v }));
  const samples: ServoSamples[] = ids.map((id) => ({
    temp: mid(byTemp.get(id) ?? none),
    volt: byVolt.get(id) ?? none,
    angle: mid(byAngle.get(id) ?? none),
  }));
  const gridStart = Math.floor(p.startMs / step.ms) * step.ms;
  const traces = thermalTraces(samples, gridStart, p.stopMs, step.ms);
  const predictions: ReturnType<typeof predictTrace>[] = [];
  const servos: ThermalServoFit[] = ids.map((id, i) => {
    const f = fitThermal(traces[i]!, o.thermalFit);
    const predicted = predictTrace(f.params, traces[i]!);
    predictions.push(predicted);
    return {
      id,
      params: f.params,
      fitted: f.fitted,
      tauFitted: f.tauFitted,
      intervals: f.intervals,
      r2: finite(f.r2),
      rmseC: finite(f.rmseC),
      voltRmseV: finite(f.voltRmseV),
      reason: f.reason,
      predicted: {
        temp: Array.from(predicted.temp, value),
        volt: Array.from(predicted.volt, value),
      },
    };
  });
  const n = traces[0]?.temp.length ?? 0;
  const volt0 = servos.map((s) => s.params.volt0V);
  const power = (volts: ArrayLike<number>[]) =>
    Array.from(armPowerW(volt0, volts, o.thermalSupplyOhms), value);
  return {
    arm: p.arm,
    start: p.startMs,
    stop: p.stopMs,
    stepMs: step.ms,
    times: Array.from({ length: n }, (_, k) => gridStart + (k + 0.5) * step.ms),
    servos,
    power: {
      supplyOhms: o.thermalSupplyOhms,
      measuredW: power(traces.map((t) => t.volt ?? [])),
      predictedW: power(predictions.map((x) => x.volt)),
    },
  };
}
