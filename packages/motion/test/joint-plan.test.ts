/**
 * Joint plans: from any pose to any pose within the limits, at any speed fraction, in either
 * profile, every sample is within the limits, no servo exceeds its speed limit, and the plan
 * starts where the arm is and ends on the target. Streamed as frames, they stay in range too.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { createReader, type Frame } from '@armtwin/protocol';
import { planJoint, samplePlan, toMoveFrames, type MotionRobot } from '../src/index.ts';
import { home, limitProblems, loadRobot } from './fixtures.ts';

const robots = { armtwin5: loadRobot('armtwin5'), track6: loadRobot('track6') };

const pose = (r: MotionRobot) =>
  fc.tuple(...r.table.map((s) => fc.double({ min: s.minPwm, max: s.maxPwm, noNaN: true })));

describe.each(Object.entries(robots))('joint plans on %s', (_, robot) => {
  it('stay within the limits and speed limits, start at the pose and end on the target', () => {
    fc.assert(
      fc.property(
        pose(robot),
        fc.array(pose(robot), { minLength: 1, maxLength: 3 }),
        fc.double({ min: 0.05, max: 1, noNaN: true }),
        fc.constantFrom('trapezoid' as const, 'linear' as const),
        (from, targets, speed, profile) => {
          const plan = planJoint(robot, from, targets, { speed, profile });
          expect(limitProblems(robot, plan, speed)).toEqual([]);
          expect(plan.samples[0]!.pwm).toEqual(from);
          expect(plan.samples.at(-1)!.pwm).toEqual(targets.at(-1));
          expect(plan.targetTimes).toHaveLength(targets.length);
          targets.forEach((t, k) => {
            const at = samplePlan(plan, plan.targetTimes[k]!);
            at.forEach((p, i) => expect(p).toBeCloseTo(t[i]!, 6));
          });
        },
      ),
      {
        numRuns: 150,
        // Found by fast-check: a segment a hair longer than a whole number of steps.
        examples:
          robot === robots.armtwin5
            ? [
                [
                  [500, 833, 500, 833, 500, 1500],
                  [
                    [2499.999975549091, 833, 500, 833, 500, 1500],
                    [500, 833, 500, 833, 500, 1500],
                  ],
                  0.9999999877705734,
                  'linear',
                ],
              ]
            : [],
      },
    );
  });

  it('are streamed as move groups within the limits, each no longer than the step', () => {
    fc.assert(
      fc.property(pose(robot), pose(robot), (from, to) => {
        const plan = planJoint(robot, from, [to], { speed: 1 });
        const frames = toMoveFrames(plan, 20);
        const last = new Map<number, number>();
        const reader = createReader({
          onGroup: (g) => {
            expect(g.invalid).toBe(0);
            for (const f of g.frames as Frame[]) {
              if (f.type !== 'move') throw new Error(`not a move: ${f.type}`);
              const i = robot.ids.indexOf(f.id);
              expect(f.pwm).toBeGreaterThanOrEqual(robot.table[i]!.minPwm);
              expect(f.pwm).toBeLessThanOrEqual(robot.table[i]!.maxPwm);
              expect(f.ms).toBeLessThanOrEqual(20);
              last.set(f.id, f.pwm);
            }
          },
          onError: (e) => {
            throw new Error(e.message);
          },
        });
        for (const f of frames) reader.feed(f.frame);
        robot.ids.forEach((id, i) => {
          if (Math.round(from[i]!) !== Math.round(to[i]!))
            expect(last.get(id)).toBe(Math.round(to[i]!));
        });
        for (let k = 1; k < frames.length; k++)
          expect(frames[k]!.at).toBeGreaterThan(frames[k - 1]!.at);
      }),
      { numRuns: 60 },
    );
  });
});

describe('joint plan timing', () => {
  it('the slowest axis sets the time: armtwin5 base 0 → 67.5° at 375°/s takes 180 ms, plus the ramp time with a trapezoid', () => {
    const r = robots.armtwin5;
    const to = home(r);
    to[0] = 2000; // 67.5°
    const linear = planJoint(r, home(r), [to], { speed: 1, profile: 'linear' });
    expect(linear.durationMs).toBeCloseTo(180, 6);
    const trap = planJoint(r, home(r), [to], { speed: 1, profile: 'trapezoid', accelMs: 100 });
    expect(trap.durationMs).toBeCloseTo(180 + 100, 6);
  });

  it('a target equal to the pose takes no time; NaN leaves a servo where it is', () => {
    const r = robots.track6;
    const plan = planJoint(r, home(r), [home(r)]);
    expect(plan.durationMs).toBe(0);
    const partial = r.ids.map(() => NaN);
    partial[1] = 1700;
    const p2 = planJoint(r, home(r), [partial]);
    expect(p2.samples.at(-1)!.pwm).toEqual(home(r).map((v, i) => (i === 1 ? 1700 : v)));
  });
});
