/**
 * Motion requests, executed by the controller core on any driver (docs/protocol.md, "Motion
 * requests"). A request (JSON) is validated, planned from the pose the driver reports (with
 * `@armtwin/motion`) and answered with feedback; `execute: true` then streams the plan into the
 * driver's goals at each `step(t)`, with pose checking: a servo off the plan (a stall) pauses the
 * arm and re-plans from where it is. An emergency stop, the deadman, a stop or any move through
 * the core, or a newer request ends an execution as `stopped`. Pure: the caller calls `step(t)`
 * every `stepMs` while `running`, and publishes the feedback returned.
 */
import {
  CODE_INVALID,
  CODE_STOPPED,
  DEFAULT_EXECUTE_OPTIONS,
  PlanExecution,
  describeDeviation,
  outcomeFeedback,
  parseRequest,
  planRequest,
  planSummary,
  type ExecuteOptions,
  type MotionFeedback,
  type MotionRobot,
} from '@armtwin/motion';
import type { ControllerCore } from './core.ts';
import { TokenBucket } from './rate-limit.ts';

export interface MotionRequestsOptions {
  /** Pose checking and streaming (`DEFAULT_EXECUTE_OPTIONS` of @armtwin/motion). */
  execute: Partial<ExecuteOptions>;
  /** Requests per second accepted, sustained; beyond it a request is answered `failed`. */
  requestRate: number;
  /** Requests accepted at once after a quiet spell. */
  requestBurst: number;
  /**
   * Whether the sender of a request (`''`: the plain topic; else the user of
   * `arm/{id}/request/{user}`) may move the arm now: '' if so, else why not (one operator at a
   * time). Unset: everyone may.
   */
  mayExecute?: (user: string) => string;
  /** Told the first time each kind of problem happens. */
  onFirst: (kind: string, message: string) => void;
  /** The arm's control topic, named when a command there ends an execution. */
  controlTopic: string;
}

export const DEFAULT_MOTION_REQUESTS_OPTIONS: MotionRequestsOptions = {
  execute: {},
  requestRate: 10,
  requestBurst: 20,
  onFirst: () => {},
  controlTopic: 'the control topic',
};

interface Running {
  id: string;
  exec: PlanExecution;
  /** Core counters when it started: a change means someone else took the arm. */
  seen: string;
  emergencyStops: number;
  deadmanStops: number;
}

export class MotionRequests {
  /** Feedback sent, by status, and refusals by kind. */
  readonly counters: Record<string, number> = {};
  readonly stepMs: number;
  private readonly o: MotionRequestsOptions;
  private readonly exo: ExecuteOptions;
  private readonly bucket: TokenBucket;
  private current: Running | undefined;

  /** `robot()`: the planner's robot now (a profile file edited while running changes it). */
  constructor(
    private readonly core: ControllerCore,
    private readonly robot: () => MotionRobot,
    now: number,
    options: Partial<MotionRequestsOptions> = {},
  ) {
    this.o = { ...DEFAULT_MOTION_REQUESTS_OPTIONS, ...options };
    this.exo = { ...DEFAULT_EXECUTE_OPTIONS, ...this.o.execute };
    this.stepMs = this.exo.stepMs;
    this.bucket = new TokenBucket(this.o.requestRate, this.o.requestBurst, now);
  }

  /** Whether a plan is being executed (call `step` every `stepMs`). */
  get running(): boolean {
    return this.current !== undefined;
  }

  /** Ends an execution without a word (the controller stops). */
  stop(): void {
    this.current = undefined;
  }

  /** A request received at t from `user` ('' = the plain topic): the feedback to send. */
  request(payload: Uint8Array | string, user: string, t: number): MotionFeedback[] {
    const out: MotionFeedback[] = [];
    const text = typeof payload === 'string' ? payload : Buffer.from(payload).toString('utf8');
    if (!this.bucket.take(t)) {
      this.count(
        'rateLimited',
        'request:rate-limit',
        `motion requests over ${this.o.requestRate}/s refused`,
      );
      const id = /"id"\s*:\s*"([A-Za-z0-9._:-]{1,64})"/.exec(text.slice(0, 2048))?.[1];
      return this.send(out, {
        id: id ?? null,
        status: 'failed',
        code: CODE_INVALID,
        message: 'rate limit: too many requests',
      });
    }
    const v = parseRequest(Buffer.from(text));
    if (!v.ok) {
      this.count('invalid', 'request:invalid', v.message);
      return this.send(out, {
        id: v.id,
        status: 'failed',
        code: CODE_INVALID,
        message: v.message,
        field: v.field,
      });
    }
    const req = v.request;
    const execute = req.execute === true;
    const refused = execute ? (this.o.mayExecute?.(user) ?? '') || this.core.driver.unready() : '';
    if (refused)
      return this.send(out, {
        id: req.id,
        status: 'failed',
        code: CODE_INVALID,
        message: `not executed: ${refused}`,
      });
    const pose = this.core.driver.pose(t);
    if (pose.some((p) => !Number.isFinite(p)))
      return this.send(out, {
        id: req.id,
        status: 'failed',
        code: CODE_INVALID,
        message: "not planned: the arm's pose is not known yet",
      });
    const robot = this.robot();
    const outcome = planRequest(robot, req, pose);
    const f = outcomeFeedback(req.id, outcome);
    if (outcome.status === 'planned' && !execute) f.message += ' (plan only: nothing moves)';
    this.send(out, f);
    if (outcome.status !== 'planned' || !execute) return out;
    if (this.current)
      this.send(out, {
        id: this.current.id,
        status: 'stopped',
        code: CODE_STOPPED,
        message: `stopped: superseded by request ${req.id}`,
      });
    const c = this.core.counters;
    this.current = {
      id: req.id,
      exec: new PlanExecution(robot, outcome.plan, outcome.spec, this.exo),
      seen: this.seen(),
      emergencyStops: c.emergencyStops,
      deadmanStops: c.deadmanStops,
    };
    this.send(out, {
      id: req.id,
      status: 'executing',
      code: 0,
      event: 'started',
      message: 'executing',
      replans: 0,
      ...planSummary(outcome.plan),
    });
    return this.step(t, out);
  }

  /** One streaming step at t: goals to the driver, and the feedback to send. */
  step(t: number, out: MotionFeedback[] = []): MotionFeedback[] {
    const r = this.current;
    if (!r) return out;
    const driver = this.core.driver;
    const all = this.core.joints.map((_, i) => i);
    if (this.seen() !== r.seen) {
      const c = this.core.counters;
      const why =
        c.deadmanStops > r.deadmanStops
          ? 'deadman: the operator let go'
          : c.emergencyStops > r.emergencyStops
            ? 'emergency stop (#255PDST!)'
            : `a command on ${this.o.controlTopic} took over`;
      this.current = undefined;
      return this.send(out, {
        id: r.id,
        status: 'stopped',
        code: CODE_STOPPED,
        message: `stopped: ${why}`,
      });
    }
    const step = r.exec.step(t, driver.pose(t));
    switch (step.kind) {
      case 'move':
        driver.move(
          step.pwm.map((pwm, i) => ({ i, pwm, ms: step.ms })),
          t,
        );
        break;
      case 'pause':
        driver.hold(all, t);
        this.send(out, {
          id: r.id,
          status: 'executing',
          code: 0,
          event: 'paused',
          replans: r.exec.replans,
          servo: r.exec.robot.profile.servos[step.check.worst]!.key,
          deviation: Math.round(step.check.deviation[step.check.worst]! * 10) / 10,
          message: `paused: ${describeDeviation(r.exec.robot, step.check, this.exo)}; re-planning from the actual pose in ${this.exo.pauseMs} ms`,
        });
        break;
      case 'replanned':
        this.send(out, {
          id: r.id,
          status: 'executing',
          code: 0,
          event: 'replanned',
          replans: step.replans,
          message: `re-planned from the actual pose (${step.replans} of at most ${this.exo.maxReplans})`,
          ...planSummary(step.plan),
        });
        break;
      case 'done':
        this.current = undefined;
        this.send(out, {
          id: r.id,
          status: 'done',
          code: 0,
          message: 'done',
          replans: r.exec.replans,
          ...planSummary(r.exec.plan),
        });
        break;
      case 'failed':
        this.current = undefined;
        driver.hold(all, t);
        this.send(out, {
          id: r.id,
          status: 'failed',
          code: step.code,
          message: step.message,
          replans: r.exec.replans,
        });
        break;
      case 'wait':
        break;
    }
    return out;
  }

  private seen(): string {
    const c = this.core.counters;
    return `${c.moves},${c.groups},${c.kms},${c.stops},${c.emergencyStops}`;
  }

  private count(key: string, kind: string, message: string): void {
    if ((this.counters[key] = (this.counters[key] ?? 0) + 1) === 1) this.o.onFirst(kind, message);
  }

  private send(out: MotionFeedback[], f: MotionFeedback): MotionFeedback[] {
    this.counters[f.status] = (this.counters[f.status] ?? 0) + 1;
    out.push(f);
    return out;
  }
}
