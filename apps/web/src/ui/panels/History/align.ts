/**
 * Series on their own times → one shared time axis (the union), a column per series with null
 * where a series has no point. What uPlot draws (`AlignedData`) and what the CSV writes. Pure.
 */

export interface TimeSeries {
  /** Column heading / legend, e.g. `Elbow` or `commanded Elbow`. */
  label: string;
  /** Epoch ms, ascending. */
  times: readonly number[];
  values: readonly number[];
}

export interface Aligned {
  labels: string[];
  /** Epoch ms, ascending, distinct. */
  times: number[];
  /** columns[k][i]: series k at times[i], or null. */
  columns: (number | null)[][];
}

export function alignSeries(series: readonly TimeSeries[]): Aligned {
  const times = [...new Set(series.flatMap((s) => s.times))].sort((a, b) => a - b);
  const index = new Map(times.map((t, i) => [t, i]));
  const columns = series.map((s) => {
    const col: (number | null)[] = new Array<number | null>(times.length).fill(null);
    s.times.forEach((t, j) => {
      const v = s.values[j];
      if (v !== undefined && Number.isFinite(v)) col[index.get(t)!] = v;
    });
    return col;
  });
  return { labels: series.map((s) => s.label), times, columns };
}

/** Points (non-null values) per series. */
export function pointCounts(a: Aligned): number[] {
  return a.columns.map((c) => c.reduce<number>((n, v) => (v === null ? n : n + 1), 0));
}

/** Largest value per series (NaN for a series without points). */
export function seriesMax(a: Aligned): number[] {
  return a.columns.map((c) =>
    c.reduce<number>((m, v) => (v === null ? m : Number.isNaN(m) ? v : Math.max(m, v)), NaN),
  );
}

/**
 * A step series (commands) held forward to `end`: its last value repeated at `end`, so a
 * command stays drawn while it is in force. Unchanged when empty or already reaching `end`.
 */
export function holdUntil(s: TimeSeries, end: number): TimeSeries {
  const last = s.times.length - 1;
  if (last < 0 || !(end > s.times[last]!)) return s;
  return { ...s, times: [...s.times, end], values: [...s.values, s.values[last]!] };
}
