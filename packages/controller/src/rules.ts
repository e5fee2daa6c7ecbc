/**
 * The rules a controller is built with, in pulse-equivalents by joint index (the unit of
 * @armtwin/motion): the keep-out check (the floor, the zones, self-collision) and the `$KMS`
 * solver. One home for both drivers: the sim and the servo bus are handed the same ones.
 */
import { checkFloorMove, keepOutReason, solveTip, type MotionRobot } from '@armtwin/motion';

/** (pulses now, pulses after the command, by joint index) → refusal reason (`floor: …`, `zone: …`) or ''. */
export type KeepOutCheck = (from: readonly number[], to: readonly number[]) => string;

/** (x, y, z mm, pitch deg or undefined, pulses now by joint index) → code and target pulses (NaN = leave). */
export type KmsSolver = (
  x: number,
  y: number,
  z: number,
  alpha: number | undefined,
  pwm: readonly number[],
) => { code: number; pwm: readonly number[] };

/**
 * `$KMS` through a profile's IK (§4's analytic solver, or the numeric one of a URDF chain):
 * without a pitch, a position-only target; with one, position + the tool axis at that pitch.
 * Seeded from the pose the arm is in. Codes 0, 2, 9, 10 (docs/robots.md).
 */
export function numericKms(robot: MotionRobot): KmsSolver {
  return (x, y, z, alpha, pwm) => {
    const r = solveTip(robot, alpha === undefined ? { x, y, z } : { x, y, z, pitch: alpha }, pwm);
    return { code: r.code, pwm: r.pwm };
  };
}

/** The floor alone (docs/protocol.md, "The floor"). */
export function floorKeepOut(robot: MotionRobot): KeepOutCheck {
  return (from, to) => {
    const c = checkFloorMove(robot, from, to);
    return c.ok ? '' : `floor: ${c.message}`;
  };
}

/**
 * The floor, the keep-out zones and self-collision (docs/protocol.md, "Keep-out zones"): the
 * goal pose against the floor, the straight path to it against the zones.
 */
export function zonesKeepOut(robot: MotionRobot): KeepOutCheck {
  return (from, to) => keepOutReason(robot, from, to);
}

/** What every move is answered while the profile file does not parse (the arm stays stopped). */
export const INVALID_PROFILE_REASON = 'zone: profile.json invalid';

/** The keep-out check in force while the profile file does not parse: every move refused. */
export const refuseEveryMove: KeepOutCheck = () => INVALID_PROFILE_REASON;
