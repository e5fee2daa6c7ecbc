/**
 * LeRobot's calibration ↔ armtwin's bus calibration: the mapping on a file as LeRobot writes it
 * for an SO-101, every calibration round-tripping tick for tick (fast-check), the matching of
 * motors to profile servos, and the refusals, each naming its motor.
 */
import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import {
  busCalibrationFromLerobot,
  lerobotCalibrationOf,
  lerobotFromBusCalibration,
  matchLerobotCalibration,
  parseLerobotCalibration,
  type LerobotMotorCalibration,
} from '../src/index.ts';

/** A calibration file as LeRobot 0.6's `so101_follower` writes it (shape and magnitudes). */
const FILE = {
  shoulder_pan: { id: 1, drive_mode: 0, homing_offset: -1470, range_min: 758, range_max: 3292 },
  shoulder_lift: { id: 2, drive_mode: 0, homing_offset: 157, range_min: 612, range_max: 3401 },
  elbow_flex: { id: 3, drive_mode: 0, homing_offset: 1105, range_min: 889, range_max: 3096 },
  wrist_flex: { id: 4, drive_mode: 0, homing_offset: -1330, range_min: 857, range_max: 3289 },
  wrist_roll: { id: 5, drive_mode: 0, homing_offset: 75, range_min: 146, range_max: 3929 },
  gripper: { id: 6, drive_mode: 0, homing_offset: 1407, range_min: 2031, range_max: 3476 },
};
const SERVOS = Object.entries(FILE).map(([joint, m]) => ({ id: m.id, joint, name: joint }));

describe('LeRobot calibration', () => {
  test('the middle of the range is the joint zero; the ends are the limits', () => {
    const c = busCalibrationFromLerobot(FILE.shoulder_pan);
    // middle 2025 ticks = −23 ticks from the centre: −2.02°, so offset +2.02°
    expect(c).toEqual({ id: 1, polarity: 1, offset: 2.02, min: -111.35, max: 111.35 });
    const mirrored = busCalibrationFromLerobot({ ...FILE.shoulder_pan, drive_mode: 1 });
    expect(mirrored).toMatchObject({ polarity: -1, offset: -2.02, min: -111.35, max: 111.35 });
  });

  test('round trip LeRobot → armtwin → LeRobot is exact for every calibration', () => {
    const motor = fc
      .record({
        id: fc.integer({ min: 0, max: 253 }),
        drive_mode: fc.constantFrom(0, 1),
        homing_offset: fc.integer({ min: -2047, max: 2047 }),
        lo: fc.integer({ min: 0, max: 4095 }),
        hi: fc.integer({ min: 0, max: 4095 }),
      })
      .filter((r) => r.lo < r.hi)
      .map(({ lo, hi, ...r }): LerobotMotorCalibration => ({ ...r, range_min: lo, range_max: hi }));
    fc.assert(
      fc.property(motor, (m) => {
        const back = lerobotFromBusCalibration(busCalibrationFromLerobot(m), m.homing_offset);
        expect(back).toEqual(m);
      }),
      { numRuns: 2000 },
    );
  });

  test('a whole file round-trips through the profile servos it matches', () => {
    const parsed = parseLerobotCalibration(JSON.parse(JSON.stringify(FILE)));
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const matched = matchLerobotCalibration(parsed.calibration, SERVOS);
    if (!matched.ok) throw new Error(matched.errors.join('; '));
    const servos = matched.servos.map((c) => ({ ...SERVOS.find((s) => s.id === c.id)!, ...c }));
    expect(JSON.stringify(lerobotCalibrationOf(servos, matched.kept))).toBe(JSON.stringify(FILE));
    // Without what the import kept: the joint names, homing offset 0.
    expect(lerobotCalibrationOf(servos, undefined).gripper).toEqual({
      ...FILE.gripper,
      homing_offset: 0,
    });
  });

  test('a motor matches by name, else by id; a disagreeing id is refused with the fix', () => {
    const renamed = { pan: FILE.shoulder_pan };
    expect(matchLerobotCalibration(renamed, SERVOS)).toMatchObject({ ok: true });
    const wrongId = { shoulder_pan: { ...FILE.shoulder_pan, id: 7 } };
    const r = matchLerobotCalibration(wrongId, SERVOS);
    expect(r.ok).toBe(false);
    expect(!r.ok && r.errors[0]).toMatch(/LeRobot's id 7, .* id 1: set the servo's id/);
    expect(matchLerobotCalibration({ x: { ...FILE.gripper, id: 9 } }, SERVOS)).toEqual({
      ok: false,
      errors: ['x (id 9): no servo of that name or id in the profile'],
    });
  });

  test('refuses a malformed file, each mistake naming its motor', () => {
    expect(parseLerobotCalibration([])).toMatchObject({ ok: false });
    expect(parseLerobotCalibration({})).toEqual({ ok: false, errors: ['no motor in the file'] });
    const r = parseLerobotCalibration({
      a: { ...FILE.gripper, range_min: 4000 },
      b: { ...FILE.gripper, drive_mode: 2, id: 7 },
      c: { ...FILE.gripper, homing_offset: 1.5, id: 8 },
      d: { ...FILE.gripper, extra: 1, id: 9 },
      e: { ...FILE.gripper },
    });
    expect(!r.ok && r.errors).toEqual([
      'a: range_min 4000 must be below range_max 3476',
      'b: drive_mode must be 0 or 1, got 2',
      'c: homing_offset must be integers',
      'd: unknown fields extra',
      "e: id 6 is also a's",
    ]);
  });
});
