/**
 * Execution with pose checking (seed 001's algorithm), against a simulated arm that follows
 * each move linearly, or not at all for a stalled servo: an arm that follows finishes; a servo
 * that stops following pauses the arm and the plan is re-made from where it is; one that never
 * follows fails after the allowed re-plans.
 */
import { describe, expect, it } from 'vitest';
import {
  CODE_OFF_PLAN,
  PlanExecution,
  checkPose,
  planRequest,
  type ExecStep,
  type MotionRobot,
} from '../src/index.ts';
import { home, loadRobot } from './fixtures.ts';

const a5 = loadRobot('armtwin5');

/** Drives `exec` every 10 ms against a toy arm; `stalled(t)` says whether servo 0 is jammed. */
function run(
  robot: MotionRobot,
  exec: PlanExecution,
  stalled: (t: number) => boolean,
  until = 20_000,
) {
  const pos = home(robot);
  let seg = pos.map((p) => ({ from: p, to: p, t0: 0, ms: 0 }));
  const at = (t: number) =>
    seg.map((s, i) =>
      i === 0 && stalled(t)
        ? pos[0]!
        : s.ms <= 0
          ? s.to
          : s.from + (s.to - s.from) * Math.min(1, (t - s.t0) / s.ms),
    );
  const events: ExecStep[] = [];
  for (let t = 0; t <= until; t += 10) {
    const now = at(t);
    pos.splice(0, pos.length, ...now);
    const step = exec.step(t, now);
    if (step.kind === 'wait') continue;
    events.push(step);
    if (step.kind === 'move')
      seg = now.map((p, i) => ({ from: p, to: step.pwm[i]!, t0: t, ms: step.ms }));
    if (step.kind === 'pause') seg = now.map((p) => ({ from: p, to: p, t0: t, ms: 0 }));
    if (step.kind === 'done' || step.kind === 'failed') break;
  }
  return { events, kinds: events.filter((e) => e.kind !== 'move').map((e) => e.kind), pos };
}

function execution(robot: MotionRobot, target: number) {
  const r = planRequest(
    robot,
    { id: 'x', mode: 'joint', targets: [{ servos: { '000': target } }], speed: 0.3 },
    home(robot),
  );
  if (r.status !== 'planned') throw new Error(r.message);
  return new PlanExecution(robot, r.plan, r.spec, { stepMs: 20, pauseMs: 200, maxReplans: 2 });
}

describe('PlanExecution', () => {
  it('an arm that follows the plan is never paused and ends on the target', () => {
    const { kinds, pos } = run(a5, execution(a5, 2200), () => false);
    expect(kinds).toEqual(['done']);
    expect(pos[0]).toBeCloseTo(2200, 0);
  });

  it('a servo stalled for a while: pause, re-plan from the actual pose, then done', () => {
    const { events, kinds, pos } = run(a5, execution(a5, 2200), (t) => t >= 300 && t < 600);
    expect(kinds).toEqual(['pause', 'replanned', 'done']);
    const pause = events.find((e) => e.kind === 'pause')!;
    if (pause.kind !== 'pause') return;
    expect(pause.check.worst).toBe(0);
    expect(pause.check.deviation[0]).toBeGreaterThan(5);
    expect(pos[0]).toBeCloseTo(2200, 0);
  });

  it('a servo that never follows fails with code 22 after the allowed re-plans', () => {
    const { events, kinds } = run(a5, execution(a5, 2200), (t) => t >= 300);
    expect(kinds).toEqual(['pause', 'replanned', 'pause', 'replanned', 'pause', 'failed']);
    const last = events.at(-1)!;
    expect(last).toMatchObject({
      kind: 'failed',
      code: CODE_OFF_PLAN,
      message: /servo 000 is .* off the plan .* after 2 re-plans/,
    });
  });

  it('checkPose measures degrees per servo against the plan at t', () => {
    const exec = execution(a5, 2200);
    const actual = home(a5);
    actual[2] = 1500 + 2000 / 27; // 10° off on the elbow
    const c = checkPose(a5, exec.plan, 0, actual);
    expect(c.ok).toBe(false);
    expect(c.worst).toBe(2);
    expect(c.deviation[2]).toBeCloseTo(10, 9);
  });
});
