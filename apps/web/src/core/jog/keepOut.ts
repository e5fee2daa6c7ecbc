/**
 * The page's one keep-out check of a jog, whichever input made it (a slider's one-target move,
 * a hold's keep-alive, a gamepad): the move from the driven arm's pose to `to` must keep the hand
 * and every joint above the floor, and every link out of the keep-out zones and off the others.
 * The controller checks again whatever drives it; this one says why before anything is sent.
 */
import { checkKeepOutMove, type MotionRobot } from '@armtwin/motion';

export interface JogRefusal {
  message: string;
  /** The URDF joint whose child link collides ('' for the floor). */
  joint: string;
}

/**
 * Why the move `from` → `to` (pulses, servo order) is refused, or null when it is clear. Null too
 * when there is nothing to check against: no planner model, or a pose not yet reported.
 */
export function jogRefusal(
  motion: MotionRobot | null,
  from: readonly number[],
  to: readonly number[],
): JogRefusal | null {
  if (!motion || from.length !== motion.ids.length || !from.every(Number.isFinite)) return null;
  const c = checkKeepOutMove(motion, from, to);
  return c.ok ? null : { message: c.message, joint: c.joint };
}
