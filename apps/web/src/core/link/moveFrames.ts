/**
 * The wire frames of the link's moves (docs/protocol.md §8): a pulse move `#IIIPpppp Tmmmm!`, or
 * an angle move `#IIIA±ddd.ddTmmmm!` for a servo that speaks angles, each checked against the
 * servo's limits first. Pure: the arm's profile is handed in.
 */
import { angleFromPwm, encodeAngleMove, encodeMove } from '@armtwin/protocol';
import {
  findServo,
  isAngleWithinLimits,
  isWithinLimits,
  speaksAngle,
  type ArmProfile,
} from '@armtwin/ik';

/**
 * The servo angle to send instead of `pwm` when the servo speaks §8 angle frames (rounded to
 * the wire's 0.01°), NaN when it speaks pulses. `pwm` is then an exact pulse-equivalent.
 */
export function wireAngle(id: number, pwm: number, arm: ArmProfile): number {
  const spec = findServo(id, arm);
  if (!speaksAngle(spec)) return NaN;
  return Math.round(angleFromPwm(pwm, spec!.polarity) * 100) / 100;
}

/** Whether a jog to `pwm` is within the servo's limits (in degrees for an angle servo). */
export function moveAllowed(id: number, pwm: number, arm: ArmProfile): boolean {
  const deg = wireAngle(id, pwm, arm);
  return Number.isNaN(deg) ? isWithinLimits(id, pwm, arm) : isAngleWithinLimits(id, deg, arm);
}

/** Servo `id` to `pwm` in `ms`: a pulse frame, or an angle frame for an angle servo. */
export function moveFrame(id: number, pwm: number, ms: number, arm: ArmProfile): string {
  const deg = wireAngle(id, pwm, arm);
  return Number.isNaN(deg) ? encodeMove(id, pwm, ms) : encodeAngleMove(id, deg, ms);
}

/** Several servos in `ms`: one frame for one move, else one `{…}` group (one command). */
export function movesFrame(
  moves: ReadonlyArray<readonly [id: number, pwm: number]>,
  ms: number,
  arm: ArmProfile,
): string {
  const frames = moves.map(([id, pwm]) => moveFrame(id, pwm, ms, arm));
  return frames.length === 1 ? frames[0]! : `{${frames.join('')}}`;
}
