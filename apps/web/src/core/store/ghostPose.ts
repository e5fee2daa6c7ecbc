/**
 * What the ghost arm shows: the previewed IK solution while a reachable target is entered,
 * otherwise the pose this HUD last commanded, and nothing when that pose is where the arm
 * already is (a ghost inside the live arm only flickers). Pure and allocation-free (it fills
 * `out`, servo angles in degrees).
 */
import { angleFromPwm } from '@armtwin/protocol';
import type { ArmProfile } from '@armtwin/ik';

/** The ghost hides when every joint is within this of the live arm, degrees. */
export const GHOST_HIDE_WITHIN_DEG = 1;

export interface GhostInputs {
  arm: ArmProfile;
  /** Drawn servo angles of the live arm, degrees. */
  rendered: ArrayLike<number>;
  /** Commanded pulses, NaN = none. */
  commandedPwm: ArrayLike<number>;
  /** Preview active and reachable, and its servo angles (NaN = servo not in the solution). */
  previewOk: boolean;
  previewAngles: ArrayLike<number>;
}

export function ghostPose(g: GhostInputs, out: Float64Array): 'nothing' | 'preview' | 'commanded' {
  const n = out.length;
  let differs = false;
  for (let i = 0; i < n; i++) {
    const p = g.previewOk ? (g.previewAngles[i] ?? NaN) : NaN;
    out[i] = Number.isNaN(p) ? commandedOrLive(g, i) : p;
    const live = g.rendered[i] ?? NaN;
    if (!Number.isNaN(out[i]!) && !(Math.abs(out[i]! - live) <= GHOST_HIDE_WITHIN_DEG))
      differs = true;
  }
  if (!differs) return 'nothing';
  return g.previewOk ? 'preview' : 'commanded';
}

function commandedOrLive(g: GhostInputs, i: number): number {
  const pwm = g.commandedPwm[i] ?? NaN;
  if (Number.isNaN(pwm)) return g.rendered[i] ?? 0;
  return angleFromPwm(pwm, g.arm.servos[i]?.polarity ?? 1);
}
