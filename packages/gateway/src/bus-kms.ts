/**
 * `$KMS` on a servo bus (pure): the profile's IK (§4's analytic solver, or the numeric one of a
 * URDF chain, both through `solveTip` of `@armtwin/motion`) turned to servo degrees. The IK
 * works in pulse widths, exact (fractional) ones, which `servoFromPwm` turns back into the
 * same degrees; the arm's present angles seed it.
 */
import { pwmFromServo, servoFromPwm } from '@armtwin/ik';
import {
  checkFloorMove,
  exactPwmFromServo,
  keepOutReason,
  solveTip,
  type MotionRobot,
} from '@armtwin/motion';

/** (x, y, z mm, pitch deg or undefined, degrees now by servo index) → code and target degrees (NaN = leave). */
export type BusKmsSolver = (
  x: number,
  y: number,
  z: number,
  alpha: number | undefined,
  degrees: readonly number[],
) => { code: number; degrees: number[] };

export function busKmsSolver(robot: MotionRobot): BusKmsSolver {
  const servos = robot.profile.servos;
  return (x, y, z, alpha, degrees) => {
    const seed = servos.map((s, i) =>
      pwmFromServo(s, Number.isFinite(degrees[i]) ? degrees[i]! : 0),
    );
    const r = solveTip(robot, alpha === undefined ? { x, y, z } : { x, y, z, pitch: alpha }, seed);
    return {
      code: r.code,
      degrees: r.pwm.map((p, i) => (Number.isNaN(p) ? NaN : servoFromPwm(servos[i]!, p))),
    };
  };
}

/** The `$KMS` refusal codes, declared once in @armtwin/protocol. */
export { KMS_FLOOR_CODE, KMS_LIMIT_CODE, KMS_ZONE_CODE } from '@armtwin/protocol';

/**
 * Keep-out zones on a bus (degrees by servo index, from = the positions read now, to = after
 * the command; NaN = unknown): the refusal reason, or '' when the move may run.
 */
export type BusKeepOut = (fromDeg: readonly number[], toDeg: readonly number[]) => string;

/** The floor as the bus gateway checks it: `checkFloorMove` of @armtwin/motion, in degrees. */
export function busFloorKeepOut(robot: MotionRobot): BusKeepOut {
  const servos = robot.profile.servos;
  const pwm = (deg: readonly number[]) => servos.map((s, i) => exactPwmFromServo(s, deg[i]!));
  return (fromDeg, toDeg) => {
    const c = checkFloorMove(robot, pwm(fromDeg), pwm(toDeg));
    return c.ok ? '' : `floor: ${c.message}`;
  };
}

/**
 * The floor, the keep-out zones and self-collision as the bus gateway checks them:
 * `keepOutReason` of @armtwin/motion in degrees (the goal against the floor, the straight path
 * to it against the zones), `floor: …` or `zone: …`.
 */
export function busZonesKeepOut(robot: MotionRobot): BusKeepOut {
  const servos = robot.profile.servos;
  const pwm = (deg: readonly number[]) => servos.map((s, i) => exactPwmFromServo(s, deg[i]!));
  return (fromDeg, toDeg) => keepOutReason(robot, pwm(fromDeg), pwm(toDeg));
}
