/**
 * A robot profile's servos as the bus gateway drives them (pure): bus ids are the profile's
 * wire ids, a servo's bus position is its §8 servo angle s (0° = the centre tick, 2048 of
 * 4096; s = polarity · (ticks − 2048) · 360 / 4096, so the profile's `polarity` is the mounting
 * direction, and its `offset` the joint's zero: joint = s + offset), and a joint whose limits reach
 * past half a turn either way runs multi-turn (Dynamixel extended position mode, Feetech
 * with both angle limits 0). The controller core's goals become bus goals here: `T…` turned
 * into a speed.
 */
import { servoLimits, type Profile, type ProfileServo } from '@armtwin/robot';
import type { ServoCalibration } from '@armtwin/servo-bus';

export interface BusJoint {
  id: number;
  servo: ProfileServo;
  /** Servo-angle limits, degrees. */
  min: number;
  max: number;
  /** Travel beyond ±180°: the servo is switched to multi-turn at start. */
  multiTurn: boolean;
}

/** Degrees/s asked of the servo for a move of `ms` ms when none can be worked out. */
export const BUS_MIN_SPEED_DEG_PER_S = 1;

export function busJoints(profile: Profile): BusJoint[] {
  return profile.servos.map((servo) => {
    const { min, max } = servoLimits(servo);
    return { id: servo.id, servo, min, max, multiTurn: min < -180 || max > 180 };
  });
}

/** A servo's ticks ↔ degrees on the bus: centre zero, the profile's polarity as direction. */
export const busCalibration = (j: BusJoint): ServoCalibration => ({
  id: j.id,
  direction: j.servo.polarity,
});

export const busCalibrations = (joints: readonly BusJoint[]): ServoCalibration[] =>
  joints.map(busCalibration);

/** A goal for one servo: where, and at what speed (°/s). */
export interface BusGoal {
  id: number;
  degrees: number;
  speedDegPerS: number;
}

/**
 * A goal for `degrees` (already checked by the controller core) in `ms` from `fromDeg` (the last
 * position read, NaN when unknown): the speed that arrives on time, never above the profile's
 * `maxSpeed` (0 ms = as fast as allowed).
 */
export function busGoal(joint: BusJoint, degrees: number, ms: number, fromDeg: number): BusGoal {
  const top = joint.servo.maxSpeed;
  let speed = top;
  if (ms > 0 && Number.isFinite(fromDeg))
    speed = Math.min(
      top,
      Math.max(BUS_MIN_SPEED_DEG_PER_S, Math.abs(degrees - fromDeg) / (ms / 1000)),
    );
  return { id: joint.id, degrees, speedDegPerS: speed };
}
