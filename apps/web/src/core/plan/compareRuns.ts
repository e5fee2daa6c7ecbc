/**
 * Predicted vs actual (issue 20, "rehearse, then run"): a run's trajectory as the arm (or its
 * model copy) reported it — each servo's angle, timestamped from the run's start — and the
 * tracking error of an actual run against its rehearsal, per servo: each actual sample is
 * compared with the rehearsal at the same time since the motion began (linear interpolation, the
 * rehearsal's first/last pose outside it). The runs are lined up where each first moves, not at
 * their clicks: the time from a click to the first move (the claim, the plan, the broker) is not
 * the arm's tracking. Pure.
 */

export interface RunTrace {
  /** ms since the run started, ascending. */
  readonly t: number[];
  /** `angles[i][k]`: servo k's reported angle (°) at `t[i]` (NaN = not reported). */
  readonly angles: Float64Array[];
}

export interface JointError {
  /** Servo index in the arm's profile. */
  index: number;
  /** Largest and mean |actual − predicted|, °; NaN when no sample could be compared. */
  maxDeg: number;
  meanDeg: number;
  samples: number;
}

/** Servo k of `trace` at time `t` (ms since start), linearly interpolated. */
export function traceAt(trace: RunTrace, k: number, t: number): number {
  const { t: ts, angles } = trace;
  const n = ts.length;
  if (n === 0) return NaN;
  if (t <= ts[0]!) return angles[0]![k] ?? NaN;
  if (t >= ts[n - 1]!) return angles[n - 1]![k] ?? NaN;
  let lo = 0;
  let hi = n - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (ts[mid]! <= t) lo = mid;
    else hi = mid;
  }
  const a = angles[lo]![k] ?? NaN;
  const b = angles[hi]![k] ?? NaN;
  const u = (t - ts[lo]!) / (ts[hi]! - ts[lo]!);
  return a + (b - a) * u;
}

/** A servo this far (°) from the run's first pose has moved: the motion has begun. */
export const MOTION_ONSET_DEG = 0.5;

/** When `trace` first moves (ms since its start): its first sample off its first pose; 0 if none. */
export function motionOnset(trace: RunTrace, thresholdDeg = MOTION_ONSET_DEG): number {
  const first = trace.angles[0];
  if (!first) return 0;
  for (let i = 1; i < trace.t.length; i++) {
    const a = trace.angles[i]!;
    for (let k = 0; k < a.length; k++) {
      if (Math.abs(a[k]! - first[k]!) > thresholdDeg) return trace.t[i]!;
    }
  }
  return 0;
}

/** Per servo, how far the actual run was from the rehearsal (see the file's comment). */
export function compareRuns(predicted: RunTrace, actual: RunTrace, servos: number): JointError[] {
  const out: JointError[] = [];
  const shift = motionOnset(predicted) - motionOnset(actual);
  for (let k = 0; k < servos; k++) {
    let max = 0;
    let sum = 0;
    let n = 0;
    for (let i = 0; i < actual.t.length; i++) {
      const a = actual.angles[i]![k] ?? NaN;
      const p = traceAt(predicted, k, actual.t[i]! + shift);
      if (!Number.isFinite(a) || !Number.isFinite(p)) continue;
      const e = Math.abs(a - p);
      if (e > max) max = e;
      sum += e;
      n++;
    }
    out.push({
      index: k,
      maxDeg: n ? max : NaN,
      meanDeg: n ? sum / n : NaN,
      samples: n,
    });
  }
  return out;
}
