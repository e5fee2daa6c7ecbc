/**
 * From stored samples to the uniform grid `fitThermal` reads: one cell per `stepMs`; the
 * temperature at each cell's centre (interpolated between the reports either side of it), the
 * mean voltage of the reports in each cell, and between the centres of two cells the path each
 * servo's angle travelled, divided by the step (its mean |speed|). The temperature is taken at
 * the centres, not as a cell's mean, because the motion is measured between the centres: a
 * cell's mean of reports at 2 Hz belongs to a time a quarter step off, and that shift alone
 * biases τ by several per cent. Pure.
 */
import type { ThermalTrace } from './thermal-fit.ts';

/** One stored sample: epoch ms and value. */
export interface TimedValue {
  t: number;
  v: number;
}

export interface ServoSamples {
  temp: readonly TimedValue[];
  volt: readonly TimedValue[];
  /** Servo angle, degrees, as dense as stored (or a finer windowed mean). */
  angle: readonly TimedValue[];
}

/** Per-cell means of samples in [startMs, startMs + n·stepMs); NaN for an empty cell. */
function cellMeans(samples: readonly TimedValue[], startMs: number, stepMs: number, n: number) {
  const sum = new Float64Array(n);
  const count = new Float64Array(n);
  for (const s of samples) {
    const k = Math.floor((s.t - startMs) / stepMs);
    if (k >= 0 && k < n && Number.isFinite(s.v)) {
      sum[k]! += s.v;
      count[k]!++;
    }
  }
  return Float64Array.from(sum, (x, k) => (count[k]! > 0 ? x / count[k]! : NaN));
}

/**
 * Values at the cell centres, linearly interpolated between the samples either side of each,
 * when those are at most `maxGapMs` apart (NaN otherwise).
 */
function atCentres(
  samples: readonly TimedValue[],
  startMs: number,
  stepMs: number,
  n: number,
  maxGapMs: number,
) {
  const out = new Float64Array(n).fill(NaN);
  const sorted = [...samples].filter((s) => Number.isFinite(s.v)).sort((a, b) => a.t - b.t);
  let j = 0;
  for (let k = 0; k < n; k++) {
    const c = startMs + (k + 0.5) * stepMs;
    while (j < sorted.length && sorted[j]!.t < c) j++;
    const after = sorted[j];
    const before = j > 0 ? sorted[j - 1] : undefined;
    if (after && after.t === c) out[k] = after.v;
    else if (before && after && after.t - before.t <= maxGapMs)
      out[k] = before.v + ((after.v - before.v) * (c - before.t)) / (after.t - before.t);
  }
  return out;
}

/**
 * Mean |speed| between the centres of cells k and k+1, deg/s: the path of the samples in that
 * span (joined to the last one before it). NaN when no sample falls in the span.
 */
function speeds(angle: readonly TimedValue[], startMs: number, stepMs: number, n: number) {
  const out = new Float64Array(Math.max(0, n - 1)).fill(NaN);
  const sorted = [...angle].filter((s) => Number.isFinite(s.v)).sort((a, b) => a.t - b.t);
  let j = 0;
  for (let k = 0; k + 1 < n; k++) {
    const from = startMs + (k + 0.5) * stepMs;
    const to = from + stepMs;
    while (j < sorted.length && sorted[j]!.t < from) j++;
    let path = 0;
    let seen = 0;
    let last = j > 0 ? sorted[j - 1]!.v : NaN;
    for (let i = j; i < sorted.length && sorted[i]!.t < to; i++) {
      if (Number.isFinite(last)) path += Math.abs(sorted[i]!.v - last);
      last = sorted[i]!.v;
      seen++;
    }
    if (seen > 0) out[k] = path / (stepMs / 1000);
  }
  return out;
}

/**
 * Every servo's trace on one grid; `totalSpeed` sums the servos whose speed is known. A
 * temperature is interpolated only between reports at most `maxGapMs` apart (default: two steps).
 */
export function thermalTraces(
  servos: readonly ServoSamples[],
  startMs: number,
  stopMs: number,
  stepMs: number,
  maxGapMs = 2 * stepMs,
): ThermalTrace[] {
  const n = Math.max(0, Math.floor((stopMs - startMs) / stepMs));
  const speed = servos.map((s) => speeds(s.angle, startMs, stepMs, n));
  const total = new Float64Array(Math.max(0, n - 1)).fill(NaN);
  for (let k = 0; k < total.length; k++) {
    let sum = 0;
    let known = 0;
    for (const sp of speed)
      if (Number.isFinite(sp[k]!)) {
        sum += sp[k]!;
        known++;
      }
    if (known > 0) total[k] = sum;
  }
  return servos.map((s, i) => ({
    stepS: stepMs / 1000,
    temp: atCentres(s.temp, startMs, stepMs, n, maxGapMs),
    volt: cellMeans(s.volt, startMs, stepMs, n),
    speed: speed[i]!,
    totalSpeed: total,
  }));
}
