/**
 * Result shaping: rows as `collectRows` gives them → the JSON the endpoints answer with.
 * Pure. Times become epoch ms (Flux's RFC 3339 with up to ns digits, cut to the ms).
 */
import type { Series } from '@armtwin/api';
import type { Sample } from './alarms.ts';
import { parseRfc3339 } from './time.ts';

/** One row of a query result (only the columns we `keep`). */
export type Row = Record<string, unknown>;

export type { Series };

export function rowTime(row: Row): number {
  const t = parseRfc3339(String(row._time));
  if (t === undefined) throw new Error(`unexpected _time in a query result: ${String(row._time)}`);
  return t;
}

/** Rows grouped by one string column (`id` by default), each group sorted by time. */
export function samplesBy(rows: readonly Row[], key = 'id'): Map<string, Sample[]> {
  const out = new Map<string, Sample[]>();
  for (const r of rows) {
    const k = String(r[key]);
    let list = out.get(k);
    if (!list) out.set(k, (list = []));
    list.push({ t: rowTime(r), v: Number(r._value) });
  }
  for (const list of out.values()) list.sort((a, b) => a.t - b.t);
  return out;
}

/** Per-id series, sorted by id. */
export function toSeries(rows: readonly Row[]): Series[] {
  return [...samplesBy(rows)]
    .sort(([a], [b]) => a.localeCompare(b))
    .map(([id, s]) => ({ id, times: s.map((x) => x.t), values: s.map((x) => x.v) }));
}

export interface PoseFrames {
  /** Servo ids, the order of each frame's angles. */
  ids: string[];
  /** Frame times, epoch ms, ascending. */
  times: number[];
  /** angles[frame][i] is servo ids[i]'s angle: its latest value at or before the frame, null before its first. */
  angles: (number | null)[][];
}

/** Per-id series on their own times → frames on the union of the times, values held forward. */
export function toPoseFrames(series: readonly Series[]): PoseFrames {
  const ids = series.map((s) => s.id);
  const times = [...new Set(series.flatMap((s) => s.times))].sort((a, b) => a - b);
  const cursor = series.map(() => 0);
  const held: (number | null)[] = series.map(() => null);
  const angles = times.map((t) => {
    series.forEach((s, i) => {
      while (cursor[i]! < s.times.length && s.times[cursor[i]!]! <= t) {
        held[i] = s.values[cursor[i]!]!;
        cursor[i]!++;
      }
    });
    return [...held];
  });
  return { ids, times, angles };
}
