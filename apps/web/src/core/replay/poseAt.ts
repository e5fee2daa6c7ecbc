/**
 * The recorded pose at any time: linear interpolation between the two pose frames around `t`
 * (`/history/pose`: frame times ascending, `angles[frame][k]` of servo `ids[k]`, null before
 * its first sample). Before the first frame the first pose, after the last the last. Pure and
 * allocation-free on the frame path: it fills `out` (servo angles in degrees, NaN = unknown).
 */

export interface PoseRecord {
  times: readonly number[];
  angles: readonly (readonly (number | null)[])[];
}

/** Index of the last frame at or before `t` (−1 if `t` is before the first). Binary search. */
export function frameIndex(times: readonly number[], t: number): number {
  let lo = 0;
  let hi = times.length - 1;
  if (hi < 0 || t < times[0]!) return -1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid]! <= t) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

/**
 * Column k of the record → servo index `slots[k]` of `out` (−1: not drawn). Servos without a
 * column keep their value in `out`. Returns the frame index used (−1 before the first).
 */
export function poseAt(
  rec: PoseRecord,
  slots: ArrayLike<number>,
  t: number,
  out: Float64Array,
): number {
  const n = rec.times.length;
  if (n === 0) return -1;
  const i = frameIndex(rec.times, t);
  const a = rec.angles[Math.max(0, i)]!;
  const hasNext = i >= 0 && i + 1 < n;
  const b = hasNext ? rec.angles[i + 1]! : a;
  const t0 = rec.times[Math.max(0, i)]!;
  const f = hasNext ? (t - t0) / (rec.times[i + 1]! - t0) : 0;
  for (let k = 0; k < slots.length; k++) {
    const slot = slots[k]!;
    if (slot < 0 || slot >= out.length) continue;
    const va = a[k] ?? null;
    const vb = b[k] ?? null;
    out[slot] = va === null ? NaN : vb === null ? va : va + (vb - va) * f;
  }
  return i;
}

/**
 * The record's servo ids (`"002"`) → indices into the active robot's servos, whose ids are
 * `servoIds` by index (they need not start at 0: the SO-101's are 1–6); −1 for an id it lacks.
 */
export function slotsFor(ids: readonly string[], servoIds: readonly number[]): Int16Array {
  const slots = new Int16Array(ids.length);
  ids.forEach((id, k) => {
    slots[k] = /^\d{3}$/.test(id) ? servoIds.indexOf(Number(id)) : -1;
  });
  return slots;
}
