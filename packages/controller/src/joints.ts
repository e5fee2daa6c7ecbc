/**
 * The controller's joints: what it needs of each servo to check a frame and turn it into a goal.
 * Positions and goals are exact (fractional) pulse-equivalents, µs, by joint index: the unit of
 * the planner, the IK and the keep-out rules of @armtwin/motion. Built from the sim's servo table
 * (`jointsFromArm`) or from a robot profile (`jointsFromProfile`, the servo bus's).
 */
import { servoLimitsPwm, type ArmProfile } from '@armtwin/ik';
import { servoLimits, type Profile } from '@armtwin/robot';
import { exactPwmFromServo } from '@armtwin/motion';
import { PWM_CENTRE, US_PER_DEG } from '@armtwin/protocol';

export interface Joint {
  /** Wire id (000–254). */
  id: number;
  /** Pulse limits, µs, min ≤ max. */
  minPwm: number;
  maxPwm: number;
  /** Servo-angle limits of a §8 angle frame, degrees. */
  minDeg: number;
  maxDeg: number;
  /** The pulse-equivalent of servo angle `deg` (an angle frame's target). */
  pwmOfAngle(deg: number): number;
}

export const id3 = (id: number) => String(id).padStart(3, '0');

/** The sim's servo table: §2 angles, `PWM_CENTRE + polarity · deg · US_PER_DEG`. */
export function jointsFromArm(arm: ArmProfile): Joint[] {
  return arm.servos.map((spec) => {
    const { min, max } = servoLimitsPwm(spec);
    return {
      id: spec.id,
      minPwm: min,
      maxPwm: max,
      minDeg: spec.minDeg,
      maxDeg: spec.maxDeg,
      pwmOfAngle: (deg) => PWM_CENTRE + spec.polarity * deg * US_PER_DEG,
    };
  });
}

/** A robot profile's servos (servo degrees through the profile, as a servo bus reads them). */
export function jointsFromProfile(profile: Profile): Joint[] {
  return profile.servos.map((servo) => {
    const { min, max } = servoLimits(servo);
    const a = exactPwmFromServo(servo, min);
    const b = exactPwmFromServo(servo, max);
    return {
      id: servo.id,
      minPwm: Math.min(a, b),
      maxPwm: Math.max(a, b),
      minDeg: min,
      maxDeg: max,
      pwmOfAngle: (deg) => exactPwmFromServo(servo, deg),
    };
  });
}

/** Index of joint `id`, or -1. */
export function jointIndex(joints: readonly Joint[], id: number): number {
  for (let i = 0; i < joints.length; i++) if (joints[i]!.id === id) return i;
  return -1;
}
