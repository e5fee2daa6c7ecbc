import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import { parseProfile, type UrdfJoint } from '@armtwin/robot';
import { nsFromRfc3339 } from '../src/export/recording.ts';
import { jointSamples, linkTransforms, targetSamples } from '../src/export/robot-motion.ts';

describe('nsFromRfc3339', () => {
  test('keeps every digit InfluxDB gives', () => {
    expect(nsFromRfc3339('2026-11-24T06:00:00.000123Z')).toBe(1_795_500_000_000_123_000n);
    expect(nsFromRfc3339('2026-11-24T06:00:00Z')).toBe(1_795_500_000_000_000_000n);
    expect(nsFromRfc3339('1970-01-01T00:00:00.000000001Z')).toBe(1n);
  });
  test('refuses what is not an RFC 3339 UTC time', () => {
    expect(() => nsFromRfc3339('2026-11-24 06:00')).toThrow(/not an RFC 3339/);
  });
});

const hinge = (axis: [number, number, number], rpy: [number, number, number]): UrdfJoint => ({
  name: 'j',
  type: 'revolute',
  parent: 'a',
  child: 'b',
  xyz: [0.1, 0.2, 0.3],
  rpy,
  axis,
});

describe('linkTransforms', () => {
  test('a hinge about z by 90° is the quaternion (0, 0, sin 45°, cos 45°) at its origin', () => {
    const [t] = linkTransforms([hinge([0, 0, 1], [0, 0, 0])], new Map([['j', Math.PI / 2]]));
    expect(t!.translation).toEqual([0.1, 0.2, 0.3]);
    t!.rotation.forEach((v, i) =>
      expect(v).toBeCloseTo([0, 0, Math.SQRT1_2, Math.SQRT1_2][i]!, 12),
    );
  });

  test('every rotation is a unit quaternion whose angle is the joint angle (origin without rpy)', () => {
    fc.assert(
      fc.property(
        fc.tuple(
          fc.double({ min: -1, max: 1 }),
          fc.double({ min: -1, max: 1 }),
          fc.double({ min: -1, max: 1 }),
        ),
        fc.double({ min: -3, max: 3, noNaN: true }),
        (axis, q) => {
          fc.pre(Math.hypot(...axis) > 0.1);
          const [t] = linkTransforms([hinge(axis, [0, 0, 0])], new Map([['j', q]]));
          const [, , , w] = t!.rotation;
          expect(Math.hypot(...t!.rotation)).toBeCloseTo(1, 9);
          expect(2 * Math.acos(Math.min(1, Math.abs(w)))).toBeCloseTo(Math.abs(q), 6);
        },
      ),
    );
  });
});

describe('jointSamples', () => {
  const parsed = parseProfile({
    format: 'armtwin-profile/1',
    name: 'two',
    title: 'two',
    urdf: 'two.urdf',
    ik: { kind: 'numeric', baseLink: 'a', tipLink: 'c' },
    servos: [
      { id: '000', name: 'A', joint: 'ja', type: 'revolute', min: -90, max: 90, maxSpeed: 100 },
      {
        id: '001',
        name: 'B',
        joint: 'jb',
        type: 'revolute',
        units: 'angle',
        offset: 10,
        min: -300,
        max: 300,
        maxSpeed: 100,
      },
    ],
    poses: { home: { unit: 'servo', servos: { '000': 0, '001': 0 } } },
  });
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  const profile = parsed.profile;

  test('one sample per reported instant, each servo carried forward; health is not a position', () => {
    const s = jointSamples(profile, [
      { ns: 1n, id: '000', pwm: 1500, angle: 0 },
      { ns: 1n, id: '001', angle: 350 },
      { ns: 2n, id: '000', temp: 40, volt: 7.4 },
      { ns: 3n, id: '000', pwm: 1500 + (2000 / 270) * 45, angle: 45 },
      { ns: 4n, id: '009', pwm: 2000 },
    ]);
    expect(s.map((x) => x.ns)).toEqual([1n, 3n]);
    expect(s[0]!.names).toEqual(['ja', 'jb']);
    expect(s[0]!.positions[0]).toBeCloseTo(0, 12);
    // a bus servo's angle (§8) plus its offset, in rad: 360°
    expect(s[0]!.positions[1]).toBeCloseTo(2 * Math.PI, 12);
    expect((s[1]!.positions[0]! * 180) / Math.PI).toBeCloseTo(45, 9);
    expect(s[1]!.positions[1]).toBeCloseTo(2 * Math.PI, 12);
  });
});

describe('targetSamples', () => {
  test('a joint not commanded yet holds where it was last reported; commanded ones keep their target', () => {
    const names = ['a', 'b', 'c'];
    const reported = [
      { ns: 10n, names, positions: [0.1, 0.2, NaN] },
      { ns: 20n, names, positions: [0.3, 0.4, 0.5] },
    ];
    const targets = [
      { ns: 5n, names, positions: [1, NaN, NaN] },
      { ns: 15n, names, positions: [1, NaN, NaN] },
      { ns: 25n, names, positions: [1, 2, NaN] },
    ];
    expect(targetSamples(targets, reported).map((s) => s.positions)).toEqual([
      [1, NaN, NaN], // nothing reported yet
      [1, 0.2, NaN],
      [1, 2, 0.5],
    ]);
  });
});
