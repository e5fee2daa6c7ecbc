/**
 * LeRobot's units for a profile's servo, both ways: the one home of the conversion that
 * `armtwin export --format lerobot` writes and the HUD's dataset import reads back. LeRobot's SO
 * follower (its default `use_degrees`) counts joints in degrees (armtwin's servo angle) and the
 * motor named `gripper` in 0–100 % of its range (MotorNormMode.RANGE_0_100); every motor is a
 * `<name>.pos` feature name. Pure.
 */
import type { ProfileServo } from './types.ts';

export const LEROBOT_GRIPPER = 'gripper';

type UnitServo = Pick<ProfileServo, 'name' | 'min' | 'max'>;

/** The servo's feature name in a LeRobot dataset (`shoulder_pan.pos`). */
export const lerobotMotorName = (servo: Pick<ProfileServo, 'name'>): string => `${servo.name}.pos`;

/** armtwin's servo angle (degrees) → LeRobot's value for that motor. */
export function lerobotValue(servo: UnitServo, degrees: number): number {
  if (servo.name === LEROBOT_GRIPPER)
    return ((degrees - servo.min) / (servo.max - servo.min)) * 100;
  return degrees;
}

/** LeRobot's value for that motor → armtwin's servo angle (degrees): lerobotValue's inverse. */
export function degreesFromLerobot(servo: UnitServo, value: number): number {
  if (servo.name === LEROBOT_GRIPPER) return servo.min + (value / 100) * (servo.max - servo.min);
  return value;
}
