/**
 * The statistics LeRobot keeps per feature (meta/stats.json, and per episode in
 * meta/episodes/…): per dimension min, max, mean, std (population), count and the quantiles
 * q01, q10, q50, q90, q99. Quantiles here are exact (linear between order statistics, numpy's
 * default), where LeRobot's own writer approximates them with histograms; the two agree to its
 * histogram's resolution. Pure.
 */

export const QUANTILES = { q01: 0.01, q10: 0.1, q50: 0.5, q90: 0.9, q99: 0.99 } as const;

export interface FeatureStats {
  min: number[];
  max: number[];
  mean: number[];
  std: number[];
  count: [number];
  q01: number[];
  q10: number[];
  q50: number[];
  q90: number[];
  q99: number[];
}

export const STAT_NAMES = [
  'min',
  'max',
  'mean',
  'std',
  'count',
  ...(Object.keys(QUANTILES) as (keyof typeof QUANTILES)[]),
] as const;

function quantile(sorted: readonly number[], q: number): number {
  const pos = (sorted.length - 1) * q;
  const lo = Math.floor(pos);
  const hi = Math.min(lo + 1, sorted.length - 1);
  return sorted[lo]! + (sorted[hi]! - sorted[lo]!) * (pos - lo);
}

/** Stats of `rows` (one vector per frame, all of one length ≥ 1); at least one row. */
export function featureStats(rows: readonly (readonly number[])[]): FeatureStats {
  if (rows.length === 0) throw new RangeError('no frames to take statistics of');
  const dims = rows[0]!.length;
  const out: FeatureStats = {
    min: [],
    max: [],
    mean: [],
    std: [],
    count: [rows.length],
    q01: [],
    q10: [],
    q50: [],
    q90: [],
    q99: [],
  };
  for (let d = 0; d < dims; d++) {
    const v = rows.map((r) => r[d]!).sort((a, b) => a - b);
    const mean = v.reduce((s, x) => s + x, 0) / v.length;
    out.min.push(v[0]!);
    out.max.push(v[v.length - 1]!);
    out.mean.push(mean);
    out.std.push(Math.sqrt(v.reduce((s, x) => s + (x - mean) ** 2, 0) / v.length));
    for (const [name, q] of Object.entries(QUANTILES))
      out[name as keyof typeof QUANTILES].push(quantile(v, q));
  }
  return out;
}
