/**
 * How the armtwin5 URDF (public/models/armtwin5) maps to the servos: one joint per servo, and
 * the joint value is the servo angle s of PROTOCOL.md §2 in radians. Pure: no DOM, no three.js.
 */
import { angleFromPwm, PWM_CENTRE } from '@armtwin/protocol';
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';

/** Relative to the page (the build's base is `./`). */
export const MODEL_URL = 'models/armtwin5/armtwin5.urdf';

/** URDF joint driven by servo i (000–005). */
export const SERVO_JOINTS = [
  'base_yaw',
  'shoulder',
  'elbow',
  'wrist_pitch',
  'wrist_roll',
  'gripper',
] as const;

/** The link whose origin is the gripper tip (tool centre point). */
export const TIP_LINK = 'tip';

export const SERVO_COUNT = SERVO_JOINTS.length;

const DEG = Math.PI / 180;

/** Servo angle (degrees, §2, polarity applied) for a pulse width of servo `id`. */
export function servoAngleDeg(id: number, pwm: number, arm: ArmProfile = DEMO_ARM): number {
  return angleFromPwm(pwm, arm.servos[id]?.polarity ?? 1);
}

/** URDF joint value (radians) for servo angle `deg`. */
export const jointValueFromAngle = (deg: number): number => deg * DEG;

/** The home pose: every servo at its centre pulse. */
export const HOME_PWM: readonly number[] = SERVO_JOINTS.map(() => PWM_CENTRE);
