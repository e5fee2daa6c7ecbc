/**
 * Failure codes of the numeric IK (2 out of reach, 9 joint limit, 10 orientation unreachable),
 * the URDF reader and chain builder's errors, and a fast-check property: arbitrary finite
 * targets never throw and never leave the limits.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { buildChain, parseUrdfJoints } from '../src/index.ts';
import { NUMERIC_IK_CODES, NumericIkSolver, chainFk, targetFromTransform } from '@armtwin/ik';
import { loadRobot, withinLimits } from './numeric-fixtures.ts';

const D = Math.PI / 180;
const t6 = loadRobot('track6');
const a5 = loadRobot('armtwin5');
const s6 = new NumericIkSolver(t6.chain);
const s5 = new NumericIkSolver(a5.chain);
const HOME6 = [1.5, 0, 0, 0, 0, 0, 0];
const HOME5 = [0, 0, 0, 0, 0];

describe('numeric IK failure codes', () => {
  it("2: beyond the chain's reach, or not a finite target", () => {
    expect(s6.solve({ mode: 'position', x: 9000, y: 0, z: 500 }, HOME6).code).toBe(2);
    expect(s5.solve({ mode: 'position', x: 0, y: -700, z: 100 }, HOME5).code).toBe(2);
    expect(s6.solve({ mode: 'position', x: NaN, y: 0, z: 500 }, HOME6).code).toBe(2);
    expect(s6.solve({ mode: 'pose', x: 1000, y: 0, z: 500 }, HOME6).code).toBe(2); // no rotation
    expect(s6.solve({ mode: 'axis', x: 1000, y: 0, z: 500, axis: [0, 0, 0] }, HOME6).code).toBe(2);
  });

  it('2: inside the reach bound but out of reach all the same (5-axis arm, 7.6 mm too far)', () => {
    const r = s5.solve({ mode: 'position', x: 300, y: 0, z: 300 }, HOME5);
    expect(r.code).toBe(2);
    expect(r.positionError).toBeGreaterThan(5);
    expect(withinLimits(a5.chain, r.joints)).toBe(true);
  });

  it('9: reachable only with the carriage beyond the end of its track', () => {
    for (const mode of ['pose', 'axis', 'position'] as const) {
      const target = targetFromTransform(
        chainFk(t6.chain, [3.6, 0, 60 * D, -50 * D, 0, 0, 0]),
        mode,
      );
      const r = s6.solve(target, HOME6);
      expect(r.code, mode).toBe(9);
      expect(r.joints[0]).toBeCloseTo(3, 9); // the best attempt: carriage at the end stop
    }
  });

  it('9: a gripper roll of 170° on the 5-axis arm (limit ±135°)', () => {
    const target = targetFromTransform(
      chainFk(a5.chain, [0, 20 * D, -40 * D, -30 * D, 170 * D]),
      'pose',
    );
    expect(s5.solve(target, HOME5).code).toBe(9);
  });

  it('10: the 5-axis arm can reach the point but cannot point its gripper sideways there', () => {
    const r = s5.solve({ mode: 'axis', x: 200, y: 0, z: 200, axis: [0, 1, 0] }, HOME5);
    expect(r.code).toBe(10);
    expect(NUMERIC_IK_CODES[r.code]).toBe('orientation unreachable');
  });

  it('without classify, every failure is 2', () => {
    const quick = new NumericIkSolver(a5.chain, { classify: false });
    expect(quick.solve({ mode: 'axis', x: 200, y: 0, z: 200, axis: [0, 1, 0] }, HOME5).code).toBe(
      2,
    );
  });

  it('never throws on arbitrary finite targets, and never leaves the limits', () => {
    const quick = new NumericIkSolver(t6.chain, { maxRestarts: 2, maxIterations: 30 });
    const coord = fc.double({ min: -8000, max: 8000, noNaN: true });
    const unit = fc.double({ min: -1, max: 1, noNaN: true });
    fc.assert(
      fc.property(
        coord,
        coord,
        coord,
        fc.constantFrom('position', 'axis', 'pose'),
        fc.tuple(unit, unit, unit),
        fc.array(fc.double(), { minLength: 7, maxLength: 7 }),
        (x, y, z, mode, [a, b, c], seed) => {
          // A rotation from an axis-angle vector (a, b, c)·π, so every `pose` target is a proper rotation.
          const rot = chainFk(t6.chain, [0, a * Math.PI * 0.7, 0, 0, b * 2, c * 2, 0]);
          const target = { ...targetFromTransform(rot, mode), x, y, z };
          if (mode === 'axis') target.axis = [a, b, c + 1e-3];
          const r = quick.solve(target, seed);
          expect([0, 2, 9, 10]).toContain(r.code);
          expect(withinLimits(t6.chain, r.joints)).toBe(true);
        },
      ),
      { numRuns: 60, seed: 42 },
    );
  });
});

describe('URDF reader and chain builder', () => {
  it("reads the shipped URDFs' joints (comments skipped, fixed tip joints included)", () => {
    const r = parseUrdfJoints(t6.urdf);
    expect(r.ok && r.joints.map((j) => j.name)).toEqual([
      'track',
      'a1',
      'a2',
      'a3',
      'a4',
      'a5',
      'a6',
      'tcp_joint',
    ]);
    const r5 = parseUrdfJoints(a5.urdf);
    expect(r5.ok && r5.joints.find((j) => j.name === 'finger_left')?.mimic).toBe('gripper');
  });

  it('reports malformed joints by name', () => {
    const bad = parseUrdfJoints(
      '<robot name="x"><joint name="j" type="hinge"><parent link="a"/></joint></robot>',
    );
    expect(bad.ok).toBe(false);
    if (!bad.ok)
      expect(bad.errors).toEqual([
        'joint "j" has type "hinge", not one of revolute, continuous, prismatic, fixed, floating, planar',
        'joint "j" has no <child link>',
      ]);
    expect(parseUrdfJoints('not xml').ok).toBe(false);
  });

  it('says which link or joint is missing', () => {
    const urdf = parseUrdfJoints(t6.urdf);
    if (!urdf.ok) throw new Error('unreachable');
    const noTip = buildChain(
      { ...t6.profile, ik: { ...t6.profile.ik, tipLink: 'nozzle' } },
      urdf.joints,
    );
    expect(noTip).toEqual({ ok: false, errors: ['no joint has tip link "nozzle" as its child'] });
    const noServo = buildChain(
      { ...t6.profile, servos: t6.profile.servos.filter((s) => s.joint !== 'a4') },
      urdf.joints,
    );
    expect(noServo.ok).toBe(false);
    if (!noServo.ok)
      expect(noServo.errors[0]).toMatch(
        /joint "a4" is on the chain .* but no servo in the profile drives it/,
      );
  });
});
