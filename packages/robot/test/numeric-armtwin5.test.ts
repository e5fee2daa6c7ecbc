/**
 * Numeric IK on the 5-axis arm, built from its profile and URDF, against the analytic solver of
 * PROTOCOL.md §4: random reachable targets given as position + pitch (the `axis` mode: the tool
 * axis's direction), solved from a different random seed. Where both succeed, both tips land on
 * the target; the numeric solution also satisfies §4's FK once mapped to servo angles.
 */
import { describe, expect, it } from 'vitest';
import { servoFromJoint } from '../src/index.ts';
import {
  NumericIkSolver,
  chainFk,
  forwardKinematics,
  jointsFromServoAngles,
  solveIk,
  targetFromTransform,
  type Quad,
} from '@armtwin/ik';
import {
  axisAngle,
  loadRobot,
  poseDistance,
  randomJoints,
  rng,
  withinLimits,
} from './numeric-fixtures.ts';

const { profile, chain } = loadRobot('armtwin5');
const solver = new NumericIkSolver(chain);
const RAD = 180 / Math.PI;

/** §4 pose (x, y, z, α) and yaw q0 of chain joint values, through servo angles and DEMO_ARM's FK. */
function section4Pose(q: ArrayLike<number>) {
  const s = [0, 1, 2, 3].map((i) =>
    servoFromJoint(profile.servos[chain.joints[i]!.servoIndex]!, q[i]!),
  ) as Quad;
  const joints = jointsFromServoAngles(s);
  return { ...forwardKinematics(joints), q0: joints.q0 };
}

/** Angle (degrees) between the tool directions (cos α cos q0, cos α sin q0, sin α) of two §4 poses. */
function dirAngle(a: { q0: number; alpha: number }, b: { q0: number; alpha: number }): number {
  const dir = (p: typeof a) => [
    Math.cos(p.alpha / RAD) * Math.cos(p.q0 / RAD),
    Math.cos(p.alpha / RAD) * Math.sin(p.q0 / RAD),
    Math.sin(p.alpha / RAD),
  ];
  const u = dir(a),
    v = dir(b);
  return Math.acos(Math.min(1, u[0]! * v[0]! + u[1]! * v[1]! + u[2]! * v[2]!)) * RAD;
}

describe('numeric IK, armtwin5 (5 axes), position + pitch', () => {
  it('reaches ≥ 99% of 300 random targets within 0.1 mm and 0.1°, and agrees with §4', () => {
    const next = rng(5);
    let ok = 0,
      both = 0,
      analyticOnly = 0,
      numericOnly = 0,
      maxMm = 0,
      maxDeg = 0,
      maxS4 = 0;
    for (let k = 0; k < 300; k++) {
      const q = randomJoints(chain, next);
      const target = chainFk(chain, q);
      const r = solver.solve(targetFromTransform(target, 'axis'), randomJoints(chain, next));
      expect(withinLimits(chain, r.joints)).toBe(true);
      const p = section4Pose(q);
      const a = solveIk(p.x, p.y, p.z, p.alpha);
      if (r.code === 0) {
        const got = chainFk(chain, r.joints);
        const mm = poseDistance(got, target).mm,
          deg = axisAngle(got, target);
        if (mm < 0.1 && deg < 0.1) ok++;
        maxMm = Math.max(maxMm, mm);
        maxDeg = Math.max(maxDeg, deg);
        // The numeric solution, read through §4's FK, is at the target with the same pitch.
        const s4 = section4Pose(r.joints);
        maxS4 = Math.max(maxS4, Math.hypot(s4.x - p.x, s4.y - p.y, s4.z - p.z));
        // Same tool direction (a mirrored pose, yaw + 180°, has α' = 180° − α: compare directions).
        expect(dirAngle(s4, p)).toBeLessThan(0.1);
      }
      if (a.code === 0 && r.code === 0) {
        both++;
        const fa = forwardKinematics(a.joints);
        expect(Math.hypot(fa.x - target[12]!, fa.y - target[13]!, fa.z - target[14]!)).toBeLessThan(
          1e-6,
        );
      } else if (a.code === 0) analyticOnly++;
      else if (r.code === 0) numericOnly++;
    }
    console.info(
      'armtwin5 axis:',
      JSON.stringify({ ok, both, analyticOnly, numericOnly, maxMm, maxDeg, maxS4 }),
    );
    expect(ok / 300).toBeGreaterThanOrEqual(0.99);
    expect(maxMm).toBeLessThan(0.1);
    expect(maxDeg).toBeLessThan(0.1);
    expect(maxS4).toBeLessThan(0.1);
    // Every target §4 solves, the numeric solver solves too (§4 misses elbow-down and behind-the-base poses).
    expect(analyticOnly).toBe(0);
    expect(both).toBeGreaterThan(100);
  });

  it("reaches the analytic solver's targets on a Cartesian grid (position + pitch)", () => {
    let tried = 0;
    for (let x = 60; x <= 300; x += 60)
      for (let z = 0; z <= 360; z += 60)
        for (const alpha of [-90, -45, 0, 45]) {
          const a = solveIk(x, 40, z, alpha);
          if (a.code !== 0) continue;
          tried++;
          const dir = [
            (Math.cos(alpha / RAD) * x) / Math.hypot(x, 40),
            (Math.cos(alpha / RAD) * 40) / Math.hypot(x, 40),
            Math.sin(alpha / RAD),
          ];
          const r = solver.solve({ mode: 'axis', x, y: 40, z, axis: dir }, [0, 0, 0, 0, 0]);
          expect(r.code, `${x} 40 ${z} α ${alpha}`).toBe(0);
          const s4 = section4Pose(r.joints);
          expect(Math.hypot(s4.x - x, s4.y - 40, s4.z - z)).toBeLessThan(0.1);
          expect(Math.abs(s4.alpha - alpha)).toBeLessThan(0.1);
        }
    expect(tried).toBeGreaterThan(20);
  });
});
