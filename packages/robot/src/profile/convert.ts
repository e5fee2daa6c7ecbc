/**
 * Servo value ↔ joint value ↔ pulse width for one profile servo, and limit checks.
 *
 * - Servo value s: a revolute servo's angle of PROTOCOL.md §2 (degrees, polarity applied); a
 *   prismatic axis's position in mm (its joint position: prismatic axes have no offset).
 * - Joint value: what the URDF joint (and the numeric IK) takes: radians or metres.
 *   Revolute: joint = (s + offset)·π/180. Prismatic: joint = s / 1000.
 * - Pulse: revolute servos follow §2 (`pwmFromAngle`, 270° over 500–2500 µs, rounded).
 *   A prismatic axis maps its pulse range linearly onto its limits: pulseMin ↔ min and
 *   pulseMax ↔ max with polarity +1, the other way round with −1; rounded to whole µs.
 */
import {
  PWM_CENTRE,
  PWM_MAX,
  PWM_MIN,
  SERVO_RANGE_DEG,
  US_PER_DEG,
  angleFromPwm,
  pwmFromAngle,
} from '@armtwin/protocol';
import type { ProfileServo } from './types.ts';

const DEG = Math.PI / 180;
/** Slack in limit checks, in the value's own unit (absorbs rounding, like IK_TOLERANCE). */
export const LIMIT_TOLERANCE = 1e-9;

/** Servo value (deg or mm) for a pulse width. Not clamped. */
export function servoFromPwm(servo: ProfileServo, pwm: number): number {
  if (servo.type === 'revolute') return angleFromPwm(pwm, servo.polarity);
  const u = (pwm - servo.pulseMin) / (servo.pulseMax - servo.pulseMin);
  return servo.polarity === 1
    ? servo.min + u * (servo.max - servo.min)
    : servo.max - u * (servo.max - servo.min);
}

/**
 * Pulse width (integer µs) for a servo value (deg or mm). Not clamped. A servo that speaks
 * angles (`units: "angle"`) never travels as a pulse: its pulse here is the exact, unrounded
 * §2 pulse-equivalent, so that its angle survives every conversion whole (350° stays 350°).
 */
export function pwmFromServo(servo: ProfileServo, s: number): number {
  if (servo.units === 'angle') return PWM_CENTRE + servo.polarity * US_PER_DEG * s;
  if (servo.type === 'revolute') return pwmFromAngle(s, servo.polarity);
  const u = (s - servo.min) / (servo.max - servo.min);
  const span = servo.pulseMax - servo.pulseMin;
  return Math.round(servo.polarity === 1 ? servo.pulseMin + u * span : servo.pulseMax - u * span);
}

/** Joint value (rad or m) for a servo value (deg or mm). */
export function jointFromServo(servo: ProfileServo, s: number): number {
  return servo.type === 'revolute' ? (s + servo.offset) * DEG : s / 1000;
}

/** Servo value (deg or mm) for a joint value (rad or m). */
export function servoFromJoint(servo: ProfileServo, q: number): number {
  return servo.type === 'revolute' ? q / DEG - servo.offset : q * 1000;
}

export const jointFromPwm = (servo: ProfileServo, pwm: number): number =>
  jointFromServo(servo, servoFromPwm(servo, pwm));

export const pwmFromJoint = (servo: ProfileServo, q: number): number =>
  pwmFromServo(servo, servoFromJoint(servo, q));

/** The joint limits in joint units (rad or m). */
export function jointLimits(servo: ProfileServo): { min: number; max: number } {
  const k = servo.type === 'revolute' ? DEG : 1 / 1000;
  return { min: servo.min * k, max: servo.max * k };
}

/** The servo-value limits (deg or mm): the joint limits less the offset. */
export function servoLimits(servo: ProfileServo): { min: number; max: number } {
  return { min: servo.min - servo.offset, max: servo.max - servo.offset };
}

/**
 * The pulses of the joint limits, `min ≤ max` whatever the polarity. Rounding is monotonic, so
 * every joint value within the limits maps to a pulse within this range.
 */
export function pwmLimits(servo: ProfileServo): { min: number; max: number } {
  const { min, max } = servoLimits(servo);
  const a = pwmFromServo(servo, min);
  const b = pwmFromServo(servo, max);
  return a <= b ? { min: a, max: b } : { min: b, max: a };
}

/** Whether a joint value (rad or m) is finite and within the limits (with `LIMIT_TOLERANCE`). */
export function jointWithinLimits(servo: ProfileServo, q: number): boolean {
  const { min, max } = jointLimits(servo);
  return Number.isFinite(q) && q >= min - LIMIT_TOLERANCE && q <= max + LIMIT_TOLERANCE;
}

/** Whether a servo value (deg or mm) is finite and within the limits. */
export function servoWithinLimits(servo: ProfileServo, s: number): boolean {
  const { min, max } = servoLimits(servo);
  return Number.isFinite(s) && s >= min - LIMIT_TOLERANCE && s <= max + LIMIT_TOLERANCE;
}

/** Whether a pulse is one the servo may be sent: finite, within `pwmLimits`. */
export function pwmWithinLimits(servo: ProfileServo, pwm: number): boolean {
  const { min, max } = pwmLimits(servo);
  return Number.isFinite(pwm) && pwm >= min && pwm <= max;
}

/** Speed limit in µs per second (what a simulator slews pulses at). */
export function maxSpeedPwm(servo: ProfileServo): number {
  if (servo.type === 'revolute') return (servo.maxSpeed * (PWM_MAX - PWM_MIN)) / SERVO_RANGE_DEG;
  return (servo.maxSpeed * (servo.pulseMax - servo.pulseMin)) / (servo.max - servo.min);
}
