/**
 * Hold-to-jog of the tool tip along x, y or z of the arm's base frame (pure): one keep-alive's
 * pose, the tip's position now plus rate × speed (mm/s) × the horizon on each held axis, its
 * pitch kept, solved through the IK as the Cartesian panel does (../cartesian/solveTarget.ts:
 * the §4 solver on the 5-axis arm, the planner's numeric IK otherwise, then the floor and the
 * keep-out zones). The page sends the solution as timed joint moves; docs/protocol.md § Hold-to-jog.
 */
import type { ArmProfile } from '@armtwin/ik';
import { tipPose, type MotionRobot } from '@armtwin/motion';
import { codeWords, solveTarget } from '../cartesian/solveTarget.ts';

export type TipAxis = 'x' | 'y' | 'z';
export const TIP_AXES: readonly TipAxis[] = ['x', 'y', 'z'];
export const isTipAxis = (v: unknown): v is TipAxis => v === 'x' || v === 'y' || v === 'z';

export type TipHold = { ok: true; pwm: number[] } | { ok: false; message: string };

/**
 * Pulses (NaN where a servo is left be) that move the tip `rates` (−1 … 1 per axis) × `speed`
 * mm/s × `horizonMs` from where the arm is (`live`, pulses, every servo known), or why not.
 */
export function tipHold(
  motion: MotionRobot,
  arm: ArmProfile,
  live: readonly number[],
  rates: Readonly<Record<TipAxis, number>>,
  speed: number,
  horizonMs: number,
): TipHold {
  if (live.length !== motion.ids.length || !live.every(Number.isFinite))
    return { ok: false, message: 'the arm has not reported every joint' };
  const tip = tipPose(motion, live);
  const step = (speed * horizonMs) / 1000;
  const r = solveTarget(
    tip.x + rates.x * step,
    tip.y + rates.y * step,
    tip.z + rates.z * step,
    Number.isFinite(tip.pitch) ? tip.pitch : undefined,
    arm,
    motion,
    live,
  );
  if (r.code !== 0)
    return { ok: false, message: r.floor ?? r.zone?.message ?? codeWords(r.code, r.via) };
  return { ok: true, pwm: r.pwm };
}
