/**
 * The profile parser: the shipped profiles parse; broken ones are refused with messages that
 * name the field; conversions honour polarity, offset and the prismatic pulse mapping.
 */
import { describe, expect, it } from 'vitest';
import {
  jointFromPwm,
  parseProfile,
  posePwm,
  pwmFromJoint,
  pwmLimits,
  pwmWithinLimits,
  servoFromPwm,
  servoTable,
  jointWithinLimits,
  type Profile,
  type ProfileServo,
} from '../src/index.ts';
import { readModelFile } from './numeric-fixtures.ts';

const raw = (name: string) =>
  JSON.parse(readModelFile(name, 'profile.json')) as Record<string, unknown>;
const parsed = (name: string): Profile => {
  const r = parseProfile(raw(name));
  if (!r.ok) throw new Error(r.errors.join('\n'));
  return r.profile;
};

/** The track6 profile with one change applied to a copy. */
// eslint-disable-next-line @typescript-eslint/no-explicit-any -- free-form edits of raw JSON
function broken(change: (p: any) => void): string[] {
  const p = structuredClone(raw('track6'));
  change(p);
  const r = parseProfile(p);
  return r.ok ? [] : r.errors;
}

describe('parseProfile', () => {
  it('accepts both shipped profiles', () => {
    expect(parsed('armtwin5').servos.map((s) => s.key)).toEqual([
      '000',
      '001',
      '002',
      '003',
      '004',
      '005',
    ]);
    expect(parsed('track6').servos.map((s) => s.joint)).toEqual([
      'track',
      'a1',
      'a2',
      'a3',
      'a4',
      'a5',
      'a6',
    ]);
  });

  it.each([
    ['not an object', () => parseProfile(42), 'profile: must be an object, got number 42'],
    [
      'wrong format',
      () => ({ ok: false, errors: broken((p) => (p.format = 'v2')) }),
      'format: must be "armtwin-profile/1", got "v2"',
    ],
    [
      'bad name',
      () => ({ ok: false, errors: broken((p) => (p.name = 'Track 6')) }),
      'name: must be 1–32 characters of a–z, 0–9, _ or -, got "Track 6"',
    ],
    [
      'bad polarity',
      () => ({ ok: false, errors: broken((p) => (p.servos[2].polarity = 0)) }),
      'servos[2].polarity: must be one of 1, -1, got number 0',
    ],
    [
      'missing joint',
      () => ({ ok: false, errors: broken((p) => delete p.servos[1].joint) }),
      'servos[1].joint: must be a non-empty string, got nothing (the field is missing)',
    ],
    [
      'typo',
      () => ({ ok: false, errors: broken((p) => (p.servos[0].maxspeed = 3)) }),
      'servos[0].maxspeed: unknown field',
    ],
    [
      'duplicate id',
      () => ({ ok: false, errors: broken((p) => (p.servos[3].id = '001')) }),
      'servos[3].id: duplicate servo id "001"',
    ],
    [
      'min ≥ max',
      () => ({ ok: false, errors: broken((p) => (p.servos[1].min = 200)) }),
      'servos[1].min: must be less than max (135), got 200',
    ],
    [
      'beyond 270°',
      () => ({ ok: false, errors: broken((p) => (p.servos[4].max = 170)) }),
      'servos[4].min: limits -135…170° (offset 0°) need pulses 241–2500 µs, outside the pulse range 500–2500',
    ],
    [
      'prismatic offset',
      () => ({ ok: false, errors: broken((p) => (p.servos[0].offset = 5)) }),
      'servos[0].offset: must be 0 (or absent) on a prismatic axis',
    ],
    [
      'bad pulse range',
      () => ({ ok: false, errors: broken((p) => (p.servos[0].pulseMax = 3000)) }),
      'servos[0].pulseMin: pulse range must satisfy 500 ≤ pulseMin < pulseMax ≤ 2500, got 500–3000',
    ],
    [
      'ik kind',
      () => ({ ok: false, errors: broken((p) => (p.ik.kind = 'fabrik')) }),
      'ik.kind: must be one of "analytic5", "numeric", got "fabrik"',
    ],
    [
      'no home',
      () => ({ ok: false, errors: broken((p) => delete p.poses.home) }),
      'poses.home: is required',
    ],
    [
      'partial home',
      () => ({ ok: false, errors: broken((p) => delete p.poses.home.servos['006']) }),
      'poses.home: must give every servo (missing 006)',
    ],
    [
      'pose unknown servo',
      () => ({ ok: false, errors: broken((p) => (p.poses.ready.servos['009'] = 0)) }),
      'poses.ready.servos.009: no servo with id "009"',
    ],
    [
      'pose over limit',
      () => ({ ok: false, errors: broken((p) => (p.poses.ready.servos['002'] = 90)) }),
      "poses.ready.servos.002: 90 ° is outside the servo's limits",
    ],
    [
      'pose pulse over limit',
      () => ({ ok: false, errors: broken((p) => (p.poses.track_end.servos['000'] = 2600)) }),
      "poses.track_end.servos.000: 2600 µs is outside the servo's limits",
    ],
  ])('refuses %s, naming the field', (_name, run, message) => {
    const r = run();
    expect(r.ok).toBe(false);
    if (!r.ok)
      expect(
        r.errors.some((e) => e.startsWith(message)),
        r.errors.join('\n'),
      ).toBe(true);
  });

  it('reports every problem at once', () => {
    const errors = broken((p) => {
      p.name = '';
      p.servos[1].polarity = 2;
      p.ik.tipLink = 7;
    });
    expect(errors.length).toBe(3);
  });
});

describe('servo ↔ joint ↔ pulse', () => {
  const track6 = parsed('track6');
  const [track, , a2, a3] = track6.servos as [
    ProfileServo,
    ProfileServo,
    ProfileServo,
    ProfileServo,
  ];

  it('maps the prismatic track linearly: 500 µs = 0 m, 2500 µs = 3 m, 1.5 mm per µs', () => {
    expect(jointFromPwm(track, 500)).toBe(0);
    expect(jointFromPwm(track, 2500)).toBe(3);
    expect(jointFromPwm(track, 1500)).toBe(1.5);
    expect(pwmFromJoint(track, 1.5)).toBe(1500);
    expect(pwmFromJoint(track, 0.0015)).toBe(501);
    const reversed = { ...track, polarity: -1 as const };
    expect(jointFromPwm(reversed, 500)).toBe(3);
    expect(pwmFromJoint(reversed, 0)).toBe(2500);
  });

  it('applies polarity −1 and the offset to a revolute servo (§2)', () => {
    // a2: polarity −1, offset 0: +20° of joint is s = 20, pwm = 1500 − 148.
    expect(pwmFromJoint(a2, (20 * Math.PI) / 180)).toBe(1352);
    // a3: offset 15°: joint 0 is s = −15 → 1389 µs; joint 145° (its max) is s = 130 → 2463 µs.
    expect(pwmFromJoint(a3, 0)).toBe(1389);
    expect(pwmFromJoint(a3, (145 * Math.PI) / 180)).toBe(2463);
    expect(servoFromPwm(a3, 1389)).toBeCloseTo(-15, 1);
    expect(jointFromPwm(a3, 1500)).toBeCloseTo((15 * Math.PI) / 180, 12);
    expect(pwmLimits(a3)).toEqual({ min: 537, max: 2463 });
  });

  it('checks limits in joint units and in pulses', () => {
    expect(jointWithinLimits(a3, (145 * Math.PI) / 180)).toBe(true);
    expect(jointWithinLimits(a3, (146 * Math.PI) / 180)).toBe(false);
    expect(jointWithinLimits(track, 3.0001)).toBe(false);
    expect(pwmWithinLimits(a2, 1870)).toBe(true);
    expect(pwmWithinLimits(a2, 1871)).toBe(false);
    expect(pwmWithinLimits(a2, NaN)).toBe(false);
  });

  it('gives the simulator its servo table: ids, pulse limits, speeds in µs/s, home pulses', () => {
    const table = servoTable(track6);
    expect(table.map((s) => s.key)).toEqual(['000', '001', '002', '003', '004', '005', '006']);
    expect(table[0]).toEqual({
      id: 0,
      key: '000',
      name: 'Track',
      type: 'prismatic',
      units: 'pulse',
      polarity: 1,
      minPwm: 500,
      maxPwm: 2500,
      maxSpeedPwmPerS: 2000 / 3,
      homePwm: 500,
    });
    expect(table[2]).toMatchObject({ minPwm: 870, maxPwm: 1870, homePwm: 1500 });
    expect(table[3]!.maxSpeedPwmPerS).toBeCloseTo((110 * 2000) / 270, 9);
    expect(table[3]!.homePwm).toBe(1389);
    expect(posePwm(track6, 'track_end')).toEqual([2500, NaN, NaN, NaN, NaN, NaN, NaN]);
    expect(posePwm(track6, 'nope')).toBeUndefined();
  });
});
