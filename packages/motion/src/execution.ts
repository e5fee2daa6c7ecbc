/**
 * Executing a plan with pose checking, as a pure state machine: the caller calls `step(t,
 * actual)` every few ms with the time (ms, any epoch) and the pulses the arm reports, and
 * carries out what it returns: `move` (send these pulses, to arrive in `ms`), `pause` (stop
 * every servo where it is), `replanned`, `done` or `failed`. The simulator drives its own
 * servos with it; a HUD would send `move` as a frame group and `pause` as stops.
 *
 * Plan time advances with the moves sent, not with the wall clock: if a step comes late the
 * arm waits at the last commanded pose and the plan waits with it, so a slow caller never
 * looks like a drifting arm. The pose the arm should be in (θ_virtual) is the plan at
 * `min(end of the move under way, its start + time since it was sent)`.
 */
import { CODE_OFF_PLAN, motionCodeMessage } from './codes.ts';
import { replanFrom, type MotionSpec, type PlanOutcome } from './motion.ts';
import { DEFAULT_EXECUTE_OPTIONS, type ExecuteOptions } from './options.ts';
import { checkPose, type PoseCheck } from './pose-check.ts';
import { samplePlan, type Plan } from './plan.ts';
import type { MotionRobot } from './robot.ts';

export type ExecStep =
  | { kind: 'move'; pwm: number[]; ms: number }
  | { kind: 'pause'; check: PoseCheck; planTime: number }
  | { kind: 'replanned'; plan: Plan; replans: number }
  | { kind: 'done' }
  | { kind: 'failed'; code: number; message: string; outcome?: PlanOutcome }
  | { kind: 'wait' };

export class PlanExecution {
  readonly options: Readonly<ExecuteOptions>;
  plan: Plan;
  replans = 0;
  state: 'running' | 'paused' | 'done' | 'failed' = 'running';
  /** The latest pose check (for feedback). */
  lastCheck: PoseCheck | undefined;
  private moveFrom = 0; // plan time at the start of the move under way
  private moveTo = 0; // plan time it runs to
  private sentAt = NaN; // when it was sent
  private pauseUntil = 0;

  constructor(
    readonly robot: MotionRobot,
    plan: Plan,
    readonly spec: MotionSpec,
    options: Partial<ExecuteOptions> = {},
  ) {
    this.options = { ...DEFAULT_EXECUTE_OPTIONS, ...options };
    this.plan = plan;
  }

  /** Plan time the arm should be at, wall time t. */
  planTime(t: number): number {
    if (Number.isNaN(this.sentAt)) return 0;
    return Math.min(this.moveTo, this.moveFrom + Math.max(0, t - this.sentAt));
  }

  step(t: number, actual: readonly number[]): ExecStep {
    if (this.state === 'done' || this.state === 'failed') return { kind: 'wait' };
    const o = this.options;
    if (this.state === 'paused') {
      if (t < this.pauseUntil) return { kind: 'wait' };
      const pt = this.moveFrom;
      if (this.replans >= o.maxReplans) {
        this.state = 'failed';
        const c = this.lastCheck!;
        return {
          kind: 'failed',
          code: CODE_OFF_PLAN,
          message: `${motionCodeMessage(CODE_OFF_PLAN)}: ${describeDeviation(this.robot, c)} after ${this.replans} re-plans`,
        };
      }
      const r = replanFrom(this.robot, this.spec, this.plan, pt, actual);
      if (r.status !== 'planned') {
        this.state = 'failed';
        return { kind: 'failed', code: r.code, message: `re-plan: ${r.message}`, outcome: r };
      }
      this.replans++;
      this.plan = r.plan;
      this.state = 'running';
      this.sentAt = NaN;
      this.moveFrom = this.moveTo = 0;
      return { kind: 'replanned', plan: r.plan, replans: this.replans };
    }
    const pt = this.planTime(t);
    const check = checkPose(this.robot, this.plan, pt, actual, o);
    this.lastCheck = check;
    if (!check.ok) {
      this.state = 'paused';
      this.pauseUntil = t + o.pauseMs;
      this.moveFrom = this.moveTo = pt;
      return { kind: 'pause', check, planTime: pt };
    }
    if (!Number.isNaN(this.sentAt) && pt < this.moveTo - 0.5) return { kind: 'wait' };
    if (this.moveTo >= this.plan.durationMs) {
      this.state = 'done';
      return { kind: 'done' };
    }
    this.moveFrom = this.moveTo;
    this.moveTo = Math.min(this.plan.durationMs, this.moveFrom + o.stepMs);
    this.sentAt = t;
    const pwm = samplePlan(this.plan, this.moveTo).map(Math.round);
    return { kind: 'move', pwm, ms: Math.ceil(this.moveTo - this.moveFrom) };
  }
}

/** "servo 001 is 7.2° off the plan (threshold 5°)". */
export function describeDeviation(
  robot: MotionRobot,
  c: PoseCheck,
  options: Partial<ExecuteOptions> = {},
): string {
  const o = { ...DEFAULT_EXECUTE_OPTIONS, ...options };
  const s = robot.profile.servos[c.worst]!;
  const unit = s.type === 'revolute' ? '°' : ' mm';
  const limit = s.type === 'revolute' ? o.thresholdDeg : o.thresholdMm;
  return `servo ${s.key} is ${c.deviation[c.worst]!.toFixed(1)}${unit} off the plan (threshold ${limit}${unit})`;
}
