/**
 * Numeric IK on the 7-axis track6 arm: random reachable targets (random joint values within
 * the limits → FK), each solved from a different random seed pose. FK(IK(p)) must land within
 * 0.1 mm and 0.1° of the target on at least 99% of them, and no solution may leave the limits.
 */
import { describe, expect, it } from 'vitest';
import { NumericIkSolver, chainFk, targetFromTransform, type TargetMode } from '@armtwin/ik';
import {
  axisAngle,
  loadRobot,
  poseDistance,
  randomJoints,
  rng,
  withinLimits,
} from './numeric-fixtures.ts';

const { chain } = loadRobot('track6');
const solver = new NumericIkSolver(chain);

function run(mode: TargetMode, n: number, seed: number) {
  const next = rng(seed);
  let ok = 0,
    maxMm = 0,
    maxDeg = 0,
    outside = 0;
  const codes: Record<number, number> = {};
  for (let k = 0; k < n; k++) {
    const target = chainFk(chain, randomJoints(chain, next));
    const r = solver.solve(targetFromTransform(target, mode), randomJoints(chain, next));
    codes[r.code] = (codes[r.code] ?? 0) + 1;
    if (!withinLimits(chain, r.joints)) outside++;
    if (r.code !== 0) continue;
    const got = chainFk(chain, r.joints);
    const d = poseDistance(got, target);
    const deg = mode === 'pose' ? d.deg : mode === 'axis' ? axisAngle(got, target) : 0;
    if (d.mm < 0.1 && deg < 0.1) ok++;
    maxMm = Math.max(maxMm, d.mm);
    maxDeg = Math.max(maxDeg, deg);
  }
  return { ok, maxMm, maxDeg, outside, codes };
}

describe('numeric IK, track6 (7 axes: prismatic track + 6 revolute)', () => {
  it('reaches ≥ 99% of 300 random position + orientation targets within 0.1 mm and 0.1°', () => {
    const r = run('pose', 300, 61);
    console.info('track6 pose:', JSON.stringify(r));
    expect(r.ok / 300).toBeGreaterThanOrEqual(0.99);
    expect(r.maxMm).toBeLessThan(0.1);
    expect(r.maxDeg).toBeLessThan(0.1);
    expect(r.outside).toBe(0);
  });

  it.each([
    ['position', 7],
    ['axis', 8],
  ] as const)('reaches ≥ 99% of 150 random %s targets', (mode, seed) => {
    const r = run(mode, 150, seed);
    console.info(`track6 ${mode}:`, JSON.stringify(r));
    expect(r.ok / 150).toBeGreaterThanOrEqual(0.99);
    expect(r.maxMm).toBeLessThan(0.1);
    expect(r.maxDeg).toBeLessThan(0.1);
    expect(r.outside).toBe(0);
  });

  it('moves only a little from a nearby seed (the current pose), and gives the same answer twice', () => {
    const next = rng(3);
    const q = randomJoints(chain, next);
    const target = targetFromTransform(chainFk(chain, q), 'pose');
    const seed = q.map((v, i) => Math.min(chain.upper[i]!, Math.max(chain.lower[i]!, v + 0.02)));
    const a = solver.solve(target, seed);
    expect(a.code).toBe(0);
    expect(a.restarts).toBe(0);
    for (let i = 0; i < chain.dof; i++) expect(Math.abs(a.joints[i]! - q[i]!)).toBeLessThan(0.1);
    const b = solver.solve(target, seed);
    expect(Array.from(b.joints)).toEqual(Array.from(a.joints));
  });
});
