/**
 * Summary statistics for benchmark samples. Pure: no clock, no I/O.
 * Percentiles interpolate linearly between the closest ranks (the "R-7" / NumPy default
 * definition), so p50 of [1, 2, 3, 4] is 2.5 and p0/p100 are the min/max.
 */

export interface Summary {
  n: number;
  mean: number;
  min: number;
  p50: number;
  p95: number;
  p99: number;
  max: number;
}

/** The p-th percentile (0–100) of ascending-sorted `sorted`; NaN when empty. */
export function percentileSorted(sorted: ArrayLike<number>, p: number): number {
  const n = sorted.length;
  if (n === 0 || !(p >= 0 && p <= 100)) return NaN;
  const rank = (p / 100) * (n - 1);
  const lo = Math.floor(rank);
  const hi = Math.min(n - 1, lo + 1);
  const a = sorted[lo]!;
  return a + (sorted[hi]! - a) * (rank - lo);
}

/** The p-th percentile of unsorted samples (copies and sorts; NaN samples are ignored). */
export function percentile(samples: ArrayLike<number>, p: number): number {
  return percentileSorted(sortedFinite(samples), p);
}

function sortedFinite(samples: ArrayLike<number>): Float64Array {
  const out = Float64Array.from(Array.prototype.filter.call(samples, Number.isFinite) as number[]);
  return out.sort();
}

/** n, mean, min, p50, p95, p99, max of the finite samples (all NaN when there are none). */
export function summarize(samples: ArrayLike<number>): Summary {
  const s = sortedFinite(samples);
  let sum = 0;
  for (const v of s) sum += v;
  const n = s.length;
  return {
    n,
    mean: n ? sum / n : NaN,
    min: n ? s[0]! : NaN,
    p50: percentileSorted(s, 50),
    p95: percentileSorted(s, 95),
    p99: percentileSorted(s, 99),
    max: n ? s[n - 1]! : NaN,
  };
}

/** Counts of samples in `bins` equal-width bins over [lo, hi); the last bin also takes ≥ hi. */
export function histogram(
  samples: ArrayLike<number>,
  lo: number,
  hi: number,
  bins: number,
): number[] {
  const counts = new Array<number>(bins).fill(0);
  const w = (hi - lo) / bins;
  for (let i = 0; i < samples.length; i++) {
    const v = samples[i]!;
    if (!Number.isFinite(v) || v < lo) continue;
    counts[Math.min(bins - 1, Math.floor((v - lo) / w))]!++;
  }
  return counts;
}

/** Rounds to `digits` significant decimals for reports (keeps NaN/null readable). */
export function round(v: number, digits = 3): number {
  if (!Number.isFinite(v)) return v;
  const f = 10 ** digits;
  return Math.round(v * f) / f;
}
