/**
 * Fits a servo's thermal and electrical model (./thermal-model.ts) to its history by linear
 * least squares. Pure. The model is linear in a = restC/τ, b = gain/τ, c = 1/τ; over an interval
 * of `spanSteps` grid steps it integrates exactly to
 *
 *   T[k+m] − T[k] = a·h + b·∫|ω|dt − c·∫T dt
 *
 * (h the interval's length), with the integrals taken by the trapezoid rule. Integrating over a
 * few steps rather than differencing one keeps the 1 °C rounding of the reports (§1 health
 * frames) from biasing c. A small ridge towards the prior keeps a history with no transient
 * (a servo that never warmed or cooled) from giving a wild τ; below `minTempSpanC` of range τ is
 * not fitted at all but kept from the prior.
 */
import { DEFAULT_THERMAL_PARAMS, stepTemperature, type ThermalParams } from './thermal-model.ts';
import { solveLinear } from '@armtwin/protocol';

/** One servo's history on a uniform time grid. */
export interface ThermalTrace {
  /** Grid step, s. */
  stepS: number;
  /** Temperature at each grid point, °C (NaN: none there). */
  temp: ArrayLike<number>;
  /** The servo's mean |speed| over step k → k+1, deg/s (NaN: unknown). */
  speed: ArrayLike<number>;
  /** Supply voltage at each grid point, V (NaN: none). */
  volt?: ArrayLike<number>;
  /** The whole arm's Σ|speed| over step k → k+1, deg/s (NaN: unknown). */
  totalSpeed?: ArrayLike<number>;
}

export interface ThermalFitOptions {
  /** Grid steps per regression interval. */
  spanSteps: number;
  /** Ridge weight towards the prior, relative to each parameter's own information. */
  ridge: number;
  /** Fewest complete intervals for a fit; fewer gives the prior (`fitted: false`). */
  minIntervals: number;
  /** Least temperature range (max − min) for τ to be fitted, °C. */
  minTempSpanC: number;
  /** τ outside this range is not believed (the prior's is kept), s. */
  minTauS: number;
  maxTauS: number;
  /** Where the ridge pulls, and what a servo with too little history gets. */
  prior: ThermalParams;
}

export const DEFAULT_THERMAL_FIT_OPTIONS: ThermalFitOptions = {
  spanSteps: 4,
  ridge: 1e-3,
  minIntervals: 20,
  minTempSpanC: 3,
  minTauS: 2,
  maxTauS: 3600,
  prior: DEFAULT_THERMAL_PARAMS,
};

export interface ThermalFit {
  params: ThermalParams;
  /** False: too little history; `params` are the prior's (`reason` says why). */
  fitted: boolean;
  /** True when τ itself was fitted (else kept from the prior). */
  tauFitted: boolean;
  /** Complete intervals used. */
  intervals: number;
  /** Fraction of the intervals' temperature change the model explains (R²; NaN with none). */
  r2: number;
  /** RMS error of the model run freely over the history from its first temperature, °C. */
  rmseC: number;
  /** RMS error of the voltage model, V (NaN with no voltage). */
  voltRmseV: number;
  reason: string;
}

/** Ridge least squares: rows of x, targets y, pulled towards `prior` by `ridge`·diag(XᵀX). */
function leastSquares(
  xs: readonly number[][],
  ys: readonly number[],
  prior: readonly number[],
  ridge: number,
): number[] | null {
  const n = prior.length;
  const a = Array.from({ length: n }, () => new Array<number>(n).fill(0));
  const b = new Array<number>(n).fill(0);
  xs.forEach((x, k) => {
    for (let i = 0; i < n; i++) {
      b[i]! += x[i]! * ys[k]!;
      for (let j = 0; j < n; j++) a[i]![j]! += x[i]! * x[j]!;
    }
  });
  for (let i = 0; i < n; i++) {
    const w = ridge * a[i]![i]! + 1e-9;
    a[i]![i]! += w;
    b[i]! += w * prior[i]!;
  }
  return solveLinear(a, b);
}

interface Interval {
  dT: number;
  h: number;
  motion: number;
  heat: number;
}

/** Intervals of m steps with every value known; `heat` is ∫(T − offsetC)dt. */
function intervals(trace: ThermalTrace, m: number, offsetC: number): Interval[] {
  const { temp, speed, stepS } = trace;
  const out: Interval[] = [];
  for (let k = 0; k + m < temp.length; k++) {
    let motion = 0;
    let heat = 0;
    let ok = true;
    for (let j = k; j < k + m && ok; j++) {
      const t0 = temp[j]!;
      const t1 = temp[j + 1]!;
      const s = speed[j]!;
      if (!Number.isFinite(t0) || !Number.isFinite(t1) || !Number.isFinite(s)) ok = false;
      motion += Math.abs(s) * stepS;
      heat += ((t0 + t1) / 2 - offsetC) * stepS;
    }
    if (ok) out.push({ dT: temp[k + m]! - temp[k]!, h: m * stepS, motion, heat });
  }
  return out;
}

/** The model run freely along the trace (re-started at the next temperature after a gap). */
export function simulateTrace(p: ThermalParams, trace: ThermalTrace): Float64Array {
  const out = new Float64Array(trace.temp.length).fill(NaN);
  let t = NaN;
  for (let k = 0; k < trace.temp.length; k++) {
    if (Number.isNaN(t) && Number.isFinite(trace.temp[k]!)) t = trace.temp[k]!;
    out[k] = t;
    const s = trace.speed[k];
    if (s === undefined || !Number.isFinite(s)) t = NaN;
    else t = stepTemperature(p, t, s, trace.stepS);
  }
  return out;
}

function rmse(a: ArrayLike<number>, b: ArrayLike<number>): number {
  let sum = 0;
  let n = 0;
  for (let k = 0; k < a.length; k++) {
    const d = a[k]! - b[k]!;
    if (Number.isFinite(d)) {
      sum += d * d;
      n++;
    }
  }
  return n > 0 ? Math.sqrt(sum / n) : NaN;
}

/** volt = v0 − sag·Σ|ω|: the supply's two parameters, or the prior's with too little data. */
function fitVolt(
  trace: ThermalTrace,
  o: ThermalFitOptions,
): { volt0V: number; sagVPerDegS: number; rmse: number } {
  const xs: number[][] = [];
  const ys: number[] = [];
  const { volt, totalSpeed } = trace;
  if (volt && totalSpeed) {
    for (let k = 0; k < volt.length; k++) {
      // The motion around the sample: the steps either side of it.
      const before = k > 0 ? totalSpeed[k - 1]! : NaN;
      const after = totalSpeed[k] ?? NaN;
      const s = Number.isFinite(before)
        ? Number.isFinite(after)
          ? (before + after) / 2
          : before
        : after;
      if (Number.isFinite(volt[k]!) && Number.isFinite(s)) {
        xs.push([1, -s]);
        ys.push(volt[k]!);
      }
    }
  }
  if (ys.length < o.minIntervals)
    return { volt0V: o.prior.volt0V, sagVPerDegS: o.prior.sagVPerDegS, rmse: NaN };
  const mean = ys.reduce((s, v) => s + v, 0) / ys.length;
  const x = leastSquares(xs, ys, [mean, 0], 0) ?? [mean, 0];
  const err = Math.sqrt(
    ys.reduce((s, y, k) => s + (y - x[0]! + x[1]! * -xs[k]![1]!) ** 2, 0) / ys.length,
  );
  return { volt0V: x[0]!, sagVPerDegS: x[1]!, rmse: err };
}

/** Fits one servo's model to its trace. */
export function fitThermal(
  trace: ThermalTrace,
  options: Partial<ThermalFitOptions> = {},
): ThermalFit {
  const o = { ...DEFAULT_THERMAL_FIT_OPTIONS, ...options };
  // Temperatures taken about their mean, so that the rest term and the cooling term are not
  // nearly the same column (which would let the ridge bias τ).
  let sum = 0;
  let count = 0;
  let lo = Infinity;
  let hi = -Infinity;
  for (let k = 0; k < trace.temp.length; k++) {
    const t = trace.temp[k]!;
    if (Number.isFinite(t)) {
      sum += t;
      count++;
      lo = Math.min(lo, t);
      hi = Math.max(hi, t);
    }
  }
  const mid = count > 0 ? sum / count : 0;
  const rows = intervals(trace, Math.max(1, Math.round(o.spanSteps)), mid);
  const v = fitVolt(trace, o);
  const none = (reason: string): ThermalFit => ({
    params: { ...o.prior, volt0V: v.volt0V, sagVPerDegS: v.sagVPerDegS },
    fitted: false,
    tauFitted: false,
    intervals: rows.length,
    r2: NaN,
    rmseC: NaN,
    voltRmseV: v.rmse,
    reason,
  });
  if (rows.length < o.minIntervals)
    return none(`${rows.length} complete intervals, fewer than ${o.minIntervals}`);

  const p = o.prior;
  // Unknowns: a = (restC − mid)/τ, b = gain/τ, c = 1/τ.
  const priorX = [(p.restC - mid) / p.tauS, p.gainCPerDegS / p.tauS, 1 / p.tauS];
  let x: number[] | null = null;
  let tauFitted = false;
  if (hi - lo >= o.minTempSpanC) {
    x = leastSquares(
      rows.map((r) => [r.h, r.motion, -r.heat]),
      rows.map((r) => r.dT),
      priorX,
      o.ridge,
    );
    const tau = x ? 1 / x[2]! : NaN;
    tauFitted = x !== null && tau >= o.minTauS && tau <= o.maxTauS;
  }
  if (!tauFitted) {
    // τ from the prior: T[k+m] − T[k] + c·∫T = a·h + b·∫|ω|.
    const c = priorX[2]!;
    const ab = leastSquares(
      rows.map((r) => [r.h, r.motion]),
      rows.map((r) => r.dT + c * r.heat),
      priorX.slice(0, 2),
      o.ridge,
    );
    if (!ab) return none('the history cannot be fitted (singular)');
    x = [ab[0]!, ab[1]!, c];
  }
  const [a, b, c] = x as [number, number, number];
  const params: ThermalParams = {
    tauS: 1 / c,
    restC: mid + a / c,
    gainCPerDegS: Math.max(0, b / c),
    volt0V: v.volt0V,
    sagVPerDegS: v.sagVPerDegS,
  };
  const meanDT = rows.reduce((s, r) => s + r.dT, 0) / rows.length;
  let ssRes = 0;
  let ssTot = 0;
  for (const r of rows) {
    ssRes += (r.dT - (a * r.h + b * r.motion - c * r.heat)) ** 2;
    ssTot += (r.dT - meanDT) ** 2;
  }
  return {
    params,
    fitted: true,
    tauFitted,
    intervals: rows.length,
    r2: ssTot > 0 ? 1 - ssRes / ssTot : NaN,
    rmseC: rmse(simulateTrace(params, trace), trace.temp),
    voltRmseV: v.rmse,
    reason: tauFitted
      ? ''
      : `temperature range ${(hi - lo).toFixed(1)} °C too small to fit τ; τ kept from the prior`,
  };
}
