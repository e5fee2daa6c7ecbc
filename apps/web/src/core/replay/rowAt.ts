/**
 * Which row of a History table stands at the replay's instant: the last row whose time is at or
 * before it (the control log's event, an alarm's start, a joint's worst moment). Rows need not
 * be in time order (the tracking table is one row per joint); a row without a time is never
 * the one. Pure: the tables sample the replay a few times a second and ask here.
 */
import { lastAtOrBefore } from './videoAt.ts';

/** The row at instant t (epoch ms), by its index in `times`; −1 when none is at or before t. */
export type RowAt = (t: number | null) => number;

/**
 * Rows' times (epoch ms, in table order; null or NaN = no time) → the row at an instant. Of
 * rows with the same time, the later one in the table is the one. Sorts once; each ask is a
 * binary search.
 */
export function rowsByTime(times: readonly (number | null)[]): RowAt {
  const order: number[] = [];
  times.forEach((t, i) => {
    if (t !== null && Number.isFinite(t)) order.push(i);
  });
  // Stable: equal times keep their table order, so the last at or before t is the later row.
  order.sort((a, b) => times[a]! - times[b]!);
  return (t) => {
    if (t === null || !Number.isFinite(t)) return -1;
    const k = lastAtOrBefore(order, t, (i) => times[i]!);
    return k < 0 ? -1 : order[k]!;
  };
}
