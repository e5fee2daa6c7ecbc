/**
 * Calibrating a bus servo: the wizard's readings become polarity, offset and limits that map
 * the readings onto the joint as it really stands, and writing them keeps the rest of the
 * profile (and the named poses' joint-space meaning) and passes the profile parser.
 */
import { describe, expect, it } from 'vitest';
import {
  applyCalibration,
  calibratedJoint,
  parseCalibrationRequest,
  parseProfile,
  solveServoCalibration,
  type Profile,
} from '../src/index.ts';
import { readModelFile } from './numeric-fixtures.ts';

/** armtwin5 with its elbow (002) a bus servo mounted the wrong way round and 20° off. */
function busRaw(): Record<string, unknown> & { servos: Record<string, unknown>[] } {
  const raw = JSON.parse(readModelFile('armtwin5', 'profile.json')) as ReturnType<typeof busRaw>;
  raw.servos[2] = {
    ...raw.servos[2],
    units: 'angle',
    polarity: -1,
    offset: 20,
    min: -150,
    max: 150,
  };
  return raw;
}
const parsed = (raw: unknown): Profile => {
  const r = parseProfile(raw);
  if (!r.ok) throw new Error(r.errors.join('\n'));
  return r.profile;
};

describe('solveServoCalibration', () => {
  const elbow = parsed(busRaw()).servos[2]!;
  // The real joint j and the raw angle t: t = j + 15 (the horn sits 15° off), and the servo in
  // force reads r = −t (polarity −1). So zero reads −15, +30° reads −45.
  const reading = (j: number) => -(j + 15);

  it('finds the direction, the zero and the travel from the readings', () => {
    const r = solveServoCalibration(elbow, {
      id: 2,
      zero: reading(0),
      positive: reading(30),
      low: reading(90),
      high: reading(-30),
    });
    expect(r).toEqual({ ok: true, fields: { id: 2, polarity: 1, offset: -15, min: -30, max: 90 } });
    if (!r.ok) return;
    // every reading now maps onto the joint where it really is
    for (const j of [-30, 0, 12.5, 90])
      expect(calibratedJoint(elbow.polarity, r.fields, reading(j))).toBeCloseTo(j, 9);
  });

  it('keeps a servo that was right as it was', () => {
    const right = { ...elbow, polarity: 1 as const, offset: 0 };
    const r = solveServoCalibration(right, { id: 2, zero: 0, positive: 10, low: -40, high: 60 });
    expect(r).toEqual({ ok: true, fields: { id: 2, polarity: 1, offset: 0, min: -40, max: 60 } });
  });

  it('refuses readings that say nothing', () => {
    const base = { id: 2, zero: 5, positive: 30, low: -40, high: 60 };
    expect(solveServoCalibration(elbow, { ...base, positive: 6 })).toMatchObject({
      ok: false,
      error: expect.stringContaining('the way the ghost leans'),
    });
    expect(solveServoCalibration(elbow, { ...base, low: 1, high: 1.5 })).toMatchObject({
      ok: false,
      error: expect.stringContaining('travel'),
    });
    expect(solveServoCalibration(elbow, { ...base, zero: NaN })).toMatchObject({ ok: false });
    const pulse = parsed(busRaw()).servos[1]!;
    expect(solveServoCalibration(pulse, base)).toMatchObject({
      ok: false,
      error: expect.stringContaining('units "angle"'),
    });
  });
});

describe('applyCalibration', () => {
  const fields = { id: 2, polarity: 1 as const, offset: -15, min: -30, max: 90 };

  it('sets the servo fields, keeps the rest, and poses keep their joint values', () => {
    const raw = busRaw();
    const before = parsed(raw);
    const r = applyCalibration(raw, [fields]);
    if (!r.ok) throw new Error(r.errors.join('\n'));
    expect(r.raw.servos).toMatchObject({
      2: { id: '002', polarity: 1, offset: -15, min: -30, max: 90 },
    });
    expect((r.raw.servos as unknown[])[1]).toEqual(raw.servos[1]);
    expect(r.raw.ik).toEqual(raw.ik);
    expect(raw.servos[2]!.offset).toBe(20); // the input is not changed
    const joint = (p: Profile, pose: string, i: number) => p.poses[pose]![i]! + p.servos[i]!.offset;
    // ready: elbow at joint −60 + 20 = −40 before; clamped into −30…90 now
    expect(joint(before, 'ready', 2)).toBe(-40);
    expect(joint(r.profile, 'ready', 2)).toBe(-30);
    // home of the others is unchanged
    for (const i of [0, 1, 3, 4, 5])
      expect(joint(r.profile, 'home', i)).toBeCloseTo(joint(before, 'home', i), 9);
    expect(Number.isNaN(r.profile.poses.open![0]!)).toBe(true);
  });

  it('refuses a servo that is not in the profile or not a bus servo', () => {
    expect(applyCalibration(busRaw(), [{ ...fields, id: 9 }])).toMatchObject({ ok: false });
    expect(applyCalibration(busRaw(), [{ ...fields, id: 1 }])).toMatchObject({
      ok: false,
      errors: [expect.stringContaining('only bus servos')],
    });
  });

  it('refuses limits the profile cannot hold', () => {
    const r = applyCalibration(busRaw(), [{ ...fields, min: 90, max: -30 }]);
    expect(r).toMatchObject({ ok: false, errors: [expect.stringContaining('servos[2].min')] });
  });
});

describe('parseCalibrationRequest', () => {
  it('reads servos and names every wrong field', () => {
    expect(
      parseCalibrationRequest({ servos: [{ id: 2, polarity: -1, offset: 1.5, min: -9, max: 9 }] }),
    ).toEqual({
      ok: true,
      servos: [{ id: 2, polarity: -1, offset: 1.5, min: -9, max: 9 }],
    });
    const bad = parseCalibrationRequest({
      servos: [{ id: 2, polarity: 2, offset: 'x', min: 0 }],
      x: 1,
    });
    expect(bad.ok).toBe(false);
    if (bad.ok) return;
    expect(bad.errors.join('\n')).toMatch(/servos\[0\]\.polarity/);
    expect(bad.errors.join('\n')).toMatch(/servos\[0\]\.offset/);
    expect(bad.errors.join('\n')).toMatch(/servos\[0\]\.max/);
    expect(bad.errors.join('\n')).toMatch(/^x: unknown field/m);
    expect(parseCalibrationRequest({ servos: [] })).toMatchObject({ ok: false });
    expect(parseCalibrationRequest('nope')).toMatchObject({ ok: false });
  });
});
