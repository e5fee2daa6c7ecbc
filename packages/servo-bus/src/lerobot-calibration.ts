/**
 * LeRobot's calibration files ↔ armtwin's bus calibration (pure). LeRobot (0.6) writes one JSON
 * file per arm, `{motor: MotorCalibration}` with `MotorCalibration = {id, drive_mode,
 * homing_offset, range_min, range_max}` (ints; positions in the servo's 0–4095 ticks after its
 * Homing_Offset register, which LeRobot writes and the servo subtracts). armtwin's profile holds
 * per servo `polarity`, `offset` and `min`/`max` (docs/protocol.md, "Bus servo calibration"):
 * s = polarity · (ticks − 2048) · 360 / 4096, joint = s + offset.
 *
 * The mapping: polarity = −1 when `drive_mode` is 1 (LeRobot mirrors about the range's middle);
 * the joint's zero is the middle of the range, as LeRobot's degrees are (and the URDF's zero of
 * the SO-101, whose description is made for them); `min`/`max` are the range's ends as joint
 * degrees, rounded inwards to 0.01°. The homing offset stays in the servo: armtwin reads the
 * positions the servo reports and never writes that register, so it is kept beside the profile
 * (`$lerobot`) only to write the same file back. Every tick survives the round trip: 0.01° is a
 * ninth of a tick.
 */
import { DEFAULT_CALIBRATION, degreesPerTick } from './units.ts';

/** LeRobot's `MotorCalibration`. */
export interface LerobotMotorCalibration {
  id: number;
  drive_mode: number;
  homing_offset: number;
  range_min: number;
  range_max: number;
}

/** A LeRobot calibration file: motor name → its calibration. */
export type LerobotCalibration = Record<string, LerobotMotorCalibration>;

/** armtwin's calibration of one bus servo (the profile's fields). */
export interface BusServoCalibration {
  id: number;
  polarity: 1 | -1;
  /** Joint degrees at servo angle 0. */
  offset: number;
  /** Joint limits, degrees. */
  min: number;
  max: number;
}

/** What the profile keeps to write the file back: per motor name, its id and homing offset. */
export type LerobotKept = Record<string, { id: number; homing_offset: number }>;

const FIELDS = ['id', 'drive_mode', 'homing_offset', 'range_min', 'range_max'] as const;
const CENTRE = DEFAULT_CALIBRATION.zeroTicks;
const PER_TICK = degreesPerTick({ id: 0 });
const round2 = (v: number) => Math.round(v * 100) / 100 + 0;

export type ParseLerobotResult =
  { ok: true; calibration: LerobotCalibration } | { ok: false; errors: string[] };

/** Checks a parsed calibration file: every motor with its five integers, ids unique. */
export function parseLerobotCalibration(json: unknown): ParseLerobotResult {
  const errors: string[] = [];
  if (typeof json !== 'object' || json === null || Array.isArray(json))
    return { ok: false, errors: ['a LeRobot calibration file is an object {motor: {...}}'] };
  const out: LerobotCalibration = {};
  const ids = new Map<number, string>();
  for (const [motor, raw] of Object.entries(json as Record<string, unknown>)) {
    if (typeof raw !== 'object' || raw === null) {
      errors.push(`${motor}: must be an object with ${FIELDS.join(', ')}`);
      continue;
    }
    const m = raw as Record<string, unknown>;
    const bad = FIELDS.filter((f) => !Number.isInteger(m[f]));
    const extra = Object.keys(m).filter((k) => !(FIELDS as readonly string[]).includes(k));
    if (bad.length) errors.push(`${motor}: ${bad.join(', ')} must be integers`);
    if (extra.length) errors.push(`${motor}: unknown fields ${extra.join(', ')}`);
    if (bad.length || extra.length) continue;
    const c = m as unknown as LerobotMotorCalibration;
    if (c.drive_mode !== 0 && c.drive_mode !== 1)
      errors.push(`${motor}: drive_mode must be 0 or 1, got ${c.drive_mode}`);
    if (!(c.range_min < c.range_max))
      errors.push(`${motor}: range_min ${c.range_min} must be below range_max ${c.range_max}`);
    if (ids.has(c.id)) errors.push(`${motor}: id ${c.id} is also ${ids.get(c.id)}'s`);
    ids.set(c.id, motor);
    out[motor] = c;
  }
  if (!errors.length && Object.keys(out).length === 0) errors.push('no motor in the file');
  return errors.length ? { ok: false, errors } : { ok: true, calibration: out };
}

/** One motor's LeRobot calibration as armtwin's. */
export function busCalibrationFromLerobot(m: LerobotMotorCalibration): BusServoCalibration {
  const polarity = m.drive_mode === 1 ? -1 : 1;
  const s = (ticks: number) => polarity * (ticks - CENTRE) * PER_TICK;
  const offset = round2(-s((m.range_min + m.range_max) / 2));
  const [a, b] = [s(m.range_min) + offset, s(m.range_max) + offset].sort((x, y) => x - y);
  return {
    id: m.id,
    polarity,
    offset,
    min: Math.ceil(a! * 100 - 1e-6) / 100 + 0,
    max: Math.floor(b! * 100 + 1e-6) / 100 + 0,
  };
}

/** armtwin's calibration of one servo as LeRobot's, with the homing offset the servo holds. */
export function lerobotFromBusCalibration(
  c: BusServoCalibration,
  homingOffset: number,
): LerobotMotorCalibration {
  const ticks = (joint: number) =>
    Math.round(CENTRE + (c.polarity * (joint - c.offset)) / PER_TICK);
  const [lo, hi] = [ticks(c.min), ticks(c.max)].sort((x, y) => x - y);
  return {
    id: c.id,
    drive_mode: c.polarity === -1 ? 1 : 0,
    homing_offset: homingOffset,
    range_min: lo!,
    range_max: hi!,
  };
}

/** A profile servo as the matching needs it. */
export interface NamedServo {
  id: number;
  /** The URDF joint and the servo's name: a LeRobot motor matches either. */
  joint: string;
  name: string;
}

export type MatchResult =
  { ok: true; servos: BusServoCalibration[]; kept: LerobotKept } | { ok: false; errors: string[] };

/**
 * Each motor of `calibration` to the profile servo of the same name (its joint or name), or of
 * the same id when no name matches; the bus ids must agree, and every motor must find a servo.
 */
export function matchLerobotCalibration(
  calibration: LerobotCalibration,
  servos: readonly NamedServo[],
): MatchResult {
  const errors: string[] = [];
  const out: BusServoCalibration[] = [];
  const kept: LerobotKept = {};
  for (const [motor, m] of Object.entries(calibration)) {
    const servo =
      servos.find((s) => s.joint === motor || s.name === motor) ??
      servos.find((s) => s.id === m.id);
    if (!servo) {
      errors.push(`${motor} (id ${m.id}): no servo of that name or id in the profile`);
      continue;
    }
    if (servo.id !== m.id) {
      errors.push(
        `${motor}: LeRobot's id ${m.id}, the profile's servo "${servo.joint}" is id ${servo.id}: set the servo's id (the profile's ids are the bus ids)`,
      );
      continue;
    }
    out.push(busCalibrationFromLerobot(m));
    kept[motor] = { id: m.id, homing_offset: m.homing_offset };
  }
  return errors.length ? { ok: false, errors } : { ok: true, servos: out, kept };
}

/**
 * The LeRobot file of a profile's servos: those named in `kept` (the imported file's motors,
 * in its order, with their homing offsets), else every servo by its joint name with homing
 * offset 0 (a servo armtwin calibrated, whose register LeRobot never set).
 */
export function lerobotCalibrationOf(
  servos: readonly (NamedServo & BusServoCalibration)[],
  kept: LerobotKept | undefined,
): LerobotCalibration {
  const out: LerobotCalibration = {};
  const entries = kept
    ? Object.entries(kept).map(
        ([motor, k]) => [motor, servos.find((s) => s.id === k.id), k] as const,
      )
    : servos.map((s) => [s.joint, s, { homing_offset: 0 }] as const);
  for (const [motor, servo, k] of entries)
    if (servo) out[motor] = lerobotFromBusCalibration(servo, k.homing_offset);
  return out;
}
