import { describe, expect, it } from 'vitest';
import { armPoints, forwardKinematics, solveIk, type Joints } from '../src/index.ts';

const MM = 1e-6;

function range(from: number, to: number, step: number): number[] {
  const out: number[] = [];
  for (let v = from; v <= to + 1e-9; v += step) out.push(v);
  return out;
}

function expectRoundTrip(x: number, y: number, z: number, alpha: number, j: Joints): void {
  const p = forwardKinematics(j);
  expect(Math.abs(p.x - x)).toBeLessThan(MM);
  expect(Math.abs(p.y - y)).toBeLessThan(MM);
  expect(Math.abs(p.z - z)).toBeLessThan(MM);
  expect(p.alpha).toBeCloseTo(alpha, 9);
}

/**
 * Whether the tip lies in front of the base axis, in the direction q0. IK takes q0 = atan2(y, x),
 * so a pose reaching back over the base (tip behind the axis) comes out as the mirrored yaw:
 * §4 cannot express it, and such poses are left out of the round trip.
 */
function inFront(p: { x: number; y: number }, q0: number): boolean {
  const rad = (q0 * Math.PI) / 180;
  return p.x * Math.cos(rad) + p.y * Math.sin(rad) > 1e-6;
}

describe('FK(IK(p)) = p within 1e-6 mm', () => {
  it('for points made by FK from joint angles inside the limits (elbow-up, θ4 ≤ 0)', () => {
    let n = 0;
    let behind = 0;
    for (const q0 of range(-130, 130, 65))
      for (const theta5 of range(5, 175, 17))
        for (const theta4 of range(-130, 0, 13))
          for (const theta3 of range(-85, 85, 17)) {
            const joints = { q0, theta5, theta4, theta3 };
            const p = forwardKinematics(joints);
            if (!inFront(p, q0)) {
              behind++;
              continue;
            }
            const r = solveIk(p.x, p.y, p.z, p.alpha);
            expect(r.code).toBe(0);
            expectRoundTrip(p.x, p.y, p.z, p.alpha, r.joints);
            // Elbow-up is the only solution with θ4 ≤ 0, so the joints come back too (to
            // 1e-5°: acos near the stretched pose θ4 = 0 loses half the digits).
            expect(Math.abs(r.joints.theta5 - theta5)).toBeLessThan(1e-5);
            expect(Math.abs(r.joints.theta4 - theta4)).toBeLessThan(1e-5);
            expect(Math.abs(r.joints.theta3 - theta3)).toBeLessThan(1e-5);
            n++;
          }
    expect(n + behind).toBe(5 * 11 * 11 * 11);
    expect(n).toBe(4690);
  });

  it('for poses exactly on the limits (the 1e-9 slack absorbs rounding)', () => {
    let n = 0;
    for (const q0 of [-135, 135])
      for (const theta5 of [0, 180])
        for (const theta3 of [-90, 90]) {
          const p = forwardKinematics({ q0, theta5, theta4: -135, theta3 });
          if (!inFront(p, q0)) continue;
          n++;
          const r = solveIk(p.x, p.y, p.z, p.alpha);
          expect(r.code).toBe(0);
          expectRoundTrip(p.x, p.y, p.z, p.alpha, r.joints);
          expect(r.joints).toEqual({ q0, theta5, theta4: -135, theta3 });
        }
    expect(n).toBe(4);
  });

  it('over a Cartesian grid at fixed pitches, keeping the accepted points', () => {
    let accepted = 0;
    let total = 0;
    for (const x of range(-350, 350, 50))
      for (const y of range(-350, 350, 50))
        for (const z of range(-50, 450, 50))
          for (const alpha of [-90, -45, 0, 45, 90]) {
            total++;
            const r = solveIk(x, y, z, alpha);
            if (r.code !== 0) continue;
            accepted++;
            expectRoundTrip(x, y, z, alpha, r.joints);
          }
    expect(total).toBe(15 * 15 * 11 * 5);
    expect(accepted).toBeGreaterThan(500);
  });

  it('over a Cartesian grid with the α search', () => {
    let accepted = 0;
    for (const x of range(-300, 300, 60))
      for (const y of range(-300, 300, 60))
        for (const z of range(0, 450, 50)) {
          const r = solveIk(x, y, z);
          if (r.code !== 0) continue;
          accepted++;
          expectRoundTrip(x, y, z, r.alpha, r.joints);
          expect(Number.isInteger(r.alpha)).toBe(true);
        }
    expect(accepted).toBeGreaterThan(200);
  });
});

describe('armPoints', () => {
  it('draws the home pose as a vertical line: shoulder 100, elbow 205, wrist 303, tip 453', () => {
    const pts = armPoints({ q0: 0, theta5: 90, theta4: 0, theta3: 0 });
    expect(pts.shoulder).toEqual({ x: 0, y: 0, z: 100 });
    for (const [p, z] of [
      [pts.elbow, 205],
      [pts.wrist, 303],
      [pts.tip, 453],
    ] as const) {
      expect(Math.hypot(p.x, p.y)).toBeLessThan(1e-12);
      expect(p.z).toBeCloseTo(z, 12);
    }
  });

  it('keeps link lengths and puts the wrist where IK puts it', () => {
    const r = solveIk(180, 120, 60, -30);
    expect(r.code).toBe(0);
    const pts = armPoints(r.joints);
    const dist = (a: typeof pts.tip, b: typeof pts.tip) =>
      Math.hypot(a.x - b.x, a.y - b.y, a.z - b.z);
    expect(dist(pts.shoulder, pts.elbow)).toBeCloseTo(105, 9);
    expect(dist(pts.elbow, pts.wrist)).toBeCloseTo(98, 9);
    expect(dist(pts.wrist, pts.tip)).toBeCloseTo(150, 9);
    const rWrist = Math.hypot(180, 120) - 150 * Math.cos((-30 * Math.PI) / 180);
    expect(Math.hypot(pts.wrist.x, pts.wrist.y)).toBeCloseTo(rWrist, 9);
    expect(pts.wrist.z).toBeCloseTo(60 - 150 * Math.sin((-30 * Math.PI) / 180), 9);
  });

  it('fills a given output object instead of allocating', () => {
    const out = armPoints({ q0: 0, theta5: 90, theta4: 0, theta3: 0 });
    const tip = out.tip;
    expect(armPoints({ q0: 90, theta5: 0, theta4: 0, theta3: 0 }, undefined, out)).toBe(out);
    expect(out.tip).toBe(tip);
    expect(out.tip.y).toBeCloseTo(353, 9);
  });
});
