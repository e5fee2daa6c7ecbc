/**
 * Calibrating a bus servo from what the HUD's wizard recorded (pure): where the joint's zero
 * is, which way it turns, and how far it goes, all as readings of the servo's §8 angle s under
 * the profile's calibration in force. The result is the profile's own fields: `polarity` (the
 * bus gateway's direction: s = polarity · (ticks − centre) · 360 / ticks per turn), `offset`
 * (joint = s + offset) and `min`/`max` (joint degrees).
 *
 * With k the polarity in force, a reading r stands for the raw angle k·r. If the joint went
 * positive while r fell (`sign` = −1), the new polarity is k·sign and the new servo angle
 * s' = sign·r, so the joint is sign·(r − zero): offset' = −sign·zero.
 */
import type { ProfileServo } from './types.ts';

/** A move under this many degrees does not tell the direction (noise, a joint that did not move). */
export const MIN_DIRECTION_DEG = 2;
/** Travel under this many degrees is not a joint's range. */
export const MIN_TRAVEL_DEG = 1;

/** What the wizard recorded for one servo: readings (servo degrees) under the calibration in force. */
export interface CalibrationSamples {
  id: number;
  /** The reading with the joint at its zero (the URDF's 0). */
  zero: number;
  /** The reading after the joint was moved the way its positive direction goes (the ghost's lean). */
  positive: number;
  /** The lowest and highest readings while the joint went through its travel. */
  low: number;
  high: number;
}

/** The profile fields a calibration sets on one servo. */
export interface ServoCalibrationFields {
  id: number;
  polarity: 1 | -1;
  /** Joint degrees at servo angle 0. */
  offset: number;
  /** Joint limits, degrees. */
  min: number;
  max: number;
}

export type CalibrationResult =
  { ok: true; fields: ServoCalibrationFields } | { ok: false; error: string };

/** To the wire's 0.01° (and no −0). */
const round2 = (v: number) => Math.round(v * 100) / 100 + 0;

/** The joint degrees a reading stands for under `fields`, given the polarity in force. */
export function calibratedJoint(
  inForce: 1 | -1,
  fields: Pick<ServoCalibrationFields, 'polarity' | 'offset'>,
  reading: number,
): number {
  return fields.polarity * inForce * reading + fields.offset;
}

export function solveServoCalibration(
  servo: ProfileServo,
  s: CalibrationSamples,
): CalibrationResult {
  const id = servo.key;
  if (servo.units !== 'angle' || servo.type !== 'revolute')
    return { ok: false, error: `servo ${id}: only bus servos (units "angle") are calibrated here` };
  const values = [s.zero, s.positive, s.low, s.high];
  if (!values.every(Number.isFinite))
    return { ok: false, error: `servo ${id}: a reading is missing` };
  const moved = s.positive - s.zero;
  if (!(Math.abs(moved) >= MIN_DIRECTION_DEG))
    return {
      ok: false,
      error: `servo ${id}: moved ${Math.abs(moved).toFixed(2)}° from zero; move it at least ${MIN_DIRECTION_DEG}° the way the ghost leans`,
    };
  if (!(s.high - s.low >= MIN_TRAVEL_DEG))
    return {
      ok: false,
      error: `servo ${id}: the recorded travel is under ${MIN_TRAVEL_DEG}°; move the joint to both ends`,
    };
  const sign = moved > 0 ? 1 : -1;
  const fields = {
    polarity: (servo.polarity * sign) as 1 | -1,
    offset: round2(-sign * s.zero),
  };
  const a = calibratedJoint(servo.polarity, fields, s.low);
  const b = calibratedJoint(servo.polarity, fields, s.high);
  return {
    ok: true,
    fields: {
      id: servo.id,
      ...fields,
      min: round2(Math.min(a, b)),
      max: round2(Math.max(a, b)),
    },
  };
}
