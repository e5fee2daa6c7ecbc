/**
 * Whether what the page sends the render worker changed since it was last sent
 * (./SceneClient.ts): pure comparisons, no allocation. NaN equals NaN here (an unset servo
 * that stays unset is no change).
 */
import type { TargetState } from './messages.ts';

/** Same length and the same numbers, NaN counted equal to NaN. */
export function sameValues(a: ArrayLike<number>, b: ArrayLike<number>): boolean {
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) {
    const x = a[i]!;
    const y = b[i]!;
    if (x !== y && !(x !== x && y !== y)) return false;
  }
  return true;
}

/** Whether the target `t` differs from the snapshot `last` (always, when there is none). */
export function targetDiffers(t: TargetState, last: TargetState | null): boolean {
  if (!last) return true;
  return (
    t.active !== last.active ||
    t.x !== last.x ||
    t.y !== last.y ||
    t.z !== last.z ||
    t.code !== last.code ||
    t.hitJoint !== last.hitJoint ||
    t.ghostEnabled !== last.ghostEnabled ||
    t.refused !== last.refused ||
    t.refusedJoint !== last.refusedJoint ||
    !sameValues(t.angles, last.angles) ||
    !sameValues(t.refusedAngles, last.refusedAngles)
  );
}
