/**
 * Cartesian plans: the tip's samples lie on the straight lines between waypoints (within
 * 0.5 mm), every pulse within the profile's range, no servo above its speed limit; unreachable
 * targets fail with the IK's code and where they failed.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  planCartesian,
  planRequest,
  posePwmOf,
  tipPose,
  type MotionRobot,
  type Plan,
} from './helpers.ts';
import { home, limitProblems, loadRobot } from './fixtures.ts';

const a5 = loadRobot('armtwin5');
const t6 = loadRobot('track6');

type P = { x: number; y: number; z: number };
function distToSegment(p: P, a: P, b: P): number {
  const ab = [b.x - a.x, b.y - a.y, b.z - a.z];
  const ap = [p.x - a.x, p.y - a.y, p.z - a.z];
  const l2 = ab[0]! ** 2 + ab[1]! ** 2 + ab[2]! ** 2;
  const u =
    l2 === 0
      ? 0
      : Math.max(0, Math.min(1, (ab[0]! * ap[0]! + ab[1]! * ap[1]! + ab[2]! * ap[2]!) / l2));
  return Math.hypot(ap[0]! - u * ab[0]!, ap[1]! - u * ab[1]!, ap[2]! - u * ab[2]!);
}

/** Largest distance (mm) of a sample's tip from the line it belongs to. */
function offLine(robot: MotionRobot, plan: Plan, from: number[], points: P[]): number {
  const ends = [tipPose(robot, from), ...points];
  let worst = 0;
  for (const s of plan.samples) {
    let seg = plan.targetTimes.findIndex((t) => s.t <= t + 1e-9);
    if (seg < 0) seg = points.length - 1;
    worst = Math.max(worst, distToSegment(tipPose(robot, s.pwm), ends[seg]!, ends[seg + 1]!));
  }
  return worst;
}

/** Tip targets the arm can reach: FK of random pulses within the limits. */
const reachable = (robot: MotionRobot) =>
  fc
    .tuple(...robot.table.map((s) => fc.double({ min: s.minPwm, max: s.maxPwm, noNaN: true })))
    .map((pwm) => tipPose(robot, pwm))
    .filter((p) => p.z > 30);

describe.each([
  ['armtwin5', a5, 80, 'ready'],
  ['track6', t6, 30, 'ready'],
] as const)('Cartesian plans on %s', (_, robot, runs, start) => {
  it('keep every sample on its line (0.5 mm), within the limits and the speed limits', () => {
    let planned = 0;
    fc.assert(
      fc.property(
        fc.array(reachable(robot), { minLength: 1, maxLength: 2 }),
        fc.double({ min: 0.1, max: 1, noNaN: true }),
        (targets, speed) => {
          const from = posePwmOf(robot, start);
          const points = targets.map(({ x, y, z }) => ({ x, y, z }));
          const r = planCartesian(
            robot,
            from,
            points.map((tip) => ({ tip })),
            { speed, linearSpeed: 400 },
          );
          if (!r.ok) {
            expect(r.code).toBeGreaterThan(0);
            return;
          }
          planned++;
          expect(limitProblems(robot, r.plan, speed)).toEqual([]);
          expect(offLine(robot, r.plan, from, points)).toBeLessThan(0.5);
        },
      ),
      { numRuns: runs },
    );
    console.info(`${robot.profile.name}: ${planned} of ${runs} random paths planned`);
    expect(planned).toBeGreaterThan(runs / 4);
  });
});

describe('Cartesian plans, examples', () => {
  it('armtwin5: a vertical line down to (200, 0, 40) keeps the gripper at its pitch (−60°)', () => {
    const from = posePwmOf(a5, 'ready');
    const r = planRequest(
      a5,
      {
        id: 'a',
        mode: 'cartesian',
        targets: [
          { x: 200, y: 0, z: 100, pitch: -60 },
          { x: 200, y: 0, z: 40, pitch: -60 },
        ],
      },
      from,
    );
    if (r.status !== 'planned') throw new Error(r.message);
    const tips = r.plan.samples
      .filter((s) => s.t >= r.plan.targetTimes[0]!)
      .map((s) => tipPose(a5, s.pwm));
    for (const p of tips) {
      expect(Math.hypot(p.x - 200, p.y)).toBeLessThan(0.5);
      expect(p.pitch).toBeCloseTo(-60, 6);
    }
    expect(tips.at(-1)!.z).toBeCloseTo(40, 6);
  });

  it('track6: a line along the track keeps the tip on it and moves the carriage', () => {
    const from = posePwmOf(t6, 'ready');
    const p0 = tipPose(t6, from);
    const r = planRequest(
      t6,
      { id: 'a', mode: 'cartesian', targets: [{ x: p0.x, y: 800, z: p0.z, pitch: -90 }] },
      from,
    );
    if (r.status !== 'planned') throw new Error(r.message);
    expect(offLine(t6, r.plan, from, [{ x: p0.x, y: 800, z: p0.z }])).toBeLessThan(0.5);
    expect(limitProblems(t6, r.plan, 0.5)).toEqual([]);
  });

  it('armtwin5: unreachable targets answer §4 codes 1, 2, 4, 6, 7 and 8 (joint mode)', () => {
    const cases: [number, number, number, number | undefined, number][] = [
      [-300, -200, -200, undefined, 1],
      [-300, -200, -50, undefined, 2],
      [-150, 0, 40, 0, 4],
      [-300, 0, 0, 0, 6],
      [-150, -200, 120, 45, 7],
      [-300, 0, 40, 0, 8],
    ];
    for (const [x, y, z, pitch, code] of cases) {
      const target = pitch === undefined ? { x, y, z } : { x, y, z, pitch };
      const r = planRequest(a5, { id: 'a', mode: 'joint', targets: [target] }, home(a5));
      expect({ status: r.status, code: r.code }, JSON.stringify(target)).toEqual({
        status: 'unreachable',
        code,
      });
    }
  });

  it('armtwin5: a line behind the base (yaw past ±135°) fails at the step where it leaves the reach', () => {
    // Both ends are reachable (yaw ±123.7°); the middle of the line is behind the arm.
    const r = planRequest(
      a5,
      {
        id: 'a',
        mode: 'cartesian',
        targets: [
          { x: -100, y: 150, z: 150 },
          { x: -100, y: -150, z: 150 },
        ],
      },
      home(a5),
    );
    expect(r.status).toBe('unreachable');
    if (r.status !== 'unreachable') return;
    expect([7, 8]).toContain(r.code); // §4's order: the wrist limit of the planned pitch comes before 8
    expect(r.target).toBe(1);
    expect(r.step).toBeGreaterThan(1);
    expect(r.message).toMatch(/^targets\[1\] step \d+ of \d+: /);
  });

  it('track6: numeric codes 2 (out of reach) and 9 (carriage past the end of the track)', () => {
    const far = planRequest(
      t6,
      { id: 'a', mode: 'joint', targets: [{ x: 9000, y: 0, z: 0 }] },
      home(t6),
    );
    expect([far.status, far.code]).toEqual(['unreachable', 2]);
    // FK of the carriage at 3.6 m (the track ends at 3 m), arm folded: reachable only past the end stop.
    const past = planRequest(
      t6,
      { id: 'a', mode: 'joint', targets: [{ x: 6559.85, y: 0, z: 1341.19 }] },
      home(t6),
    );
    expect([past.status, past.code]).toEqual(['unreachable', 9]);
  });
});
