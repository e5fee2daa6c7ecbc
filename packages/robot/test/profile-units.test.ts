/**
 * `"units": "angle"` in a profile servo: the servo speaks PROTOCOL §8 angle frames, so its
 * limits are servo angles up to ±999.99° and no longer have to fit the 500–2500 µs pulse range.
 */
import { describe, expect, it } from 'vitest';
import { parseProfile, pulseEquivalentArm, servoModelArm } from '../src/index.ts';
import { speaksAngle } from '@armtwin/ik';
import { readModelFile } from './numeric-fixtures.ts';

// eslint-disable-next-line @typescript-eslint/no-explicit-any -- free-form edits of raw JSON
function edited(name: string, change: (p: any) => void) {
  const p = JSON.parse(readModelFile(name, 'profile.json')) as Record<string, unknown>;
  change(p);
  return parseProfile(p);
}

describe('profile servo units', () => {
  it('default to pulse widths: the shipped profiles are unchanged', () => {
    for (const name of ['armtwin5', 'track6']) {
      const r = edited(name, () => {});
      expect(r.ok && r.profile.servos.every((s) => s.units === 'pulse')).toBe(true);
      if (r.ok) expect(servoModelArm(r.profile).servos.some((s) => speaksAngle(s))).toBe(false);
    }
  });

  it('an angle servo may travel ±360° (a pulse servo may not), and counts in its own servo angles', () => {
    const r = edited('track6', (p) =>
      Object.assign(p.servos[4], { units: 'angle', min: -360, max: 360, offset: 10 }),
    );
    if (!r.ok) throw new Error(r.errors.join('; '));
    const s = r.profile.servos[4]!;
    expect(s.units).toBe('angle');
    const arm = pulseEquivalentArm(r.profile).servos[4]!;
    expect(arm).toMatchObject({
      units: 'angle',
      minDeg: -370,
      maxDeg: 350,
      polarity: s.polarity,
      maxSpeedDegPerS: s.maxSpeed,
    });
    expect(pulseEquivalentArm(r.profile).servos[3]!.units).toBeUndefined();
    const pulse = edited('track6', (p) => Object.assign(p.servos[4], { min: -360, max: 360 }));
    expect(pulse.ok).toBe(false);
  });

  it('an analytic5 profile keeps the unit on its servo', () => {
    const r = edited('armtwin5', (p) =>
      Object.assign(p.servos[4], { units: 'angle', min: -360, max: 360 }),
    );
    if (!r.ok) throw new Error(r.errors.join('; '));
    expect(servoModelArm(r.profile).servos[4]).toMatchObject({
      units: 'angle',
      minDeg: -360,
      maxDeg: 360,
    });
  });

  it.each([
    [
      'an unknown unit',
      (p: { servos: Record<string, unknown>[] }) => (p.servos[4]!.units = 'steps'),
      'servos[4].units: must be one of "pulse", "angle", got "steps"',
    ],
    [
      'angles on a prismatic axis',
      (p: { servos: Record<string, unknown>[] }) => (p.servos[0]!.units = 'angle'),
      'servos[0].units: "angle" is for revolute servos only',
    ],
    [
      'beyond what an angle frame carries',
      (p: { servos: Record<string, unknown>[] }) =>
        Object.assign(p.servos[4]!, { units: 'angle', min: -1000, max: 0 }),
      'outside what an angle frame carries (±999.99°)',
    ],
  ])('refuses %s', (_, change, message) => {
    const r = edited('track6', change);
    expect(r.ok).toBe(false);
    if (!r.ok) expect(r.errors.join('\n')).toContain(message);
  });
});
