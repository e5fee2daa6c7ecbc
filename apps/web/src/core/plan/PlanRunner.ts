/**
 * Runs a plan from the HUD: a timer loop outside React steps `PlanExecution` (pose checking,
 * seed 001) with the latest pulses the store has from the arm, and streams what it says as
 * `{#IIIPppppTtttt!…}` groups on the control topic (`ArmLink.sendGroup`). On drift beyond the
 * threshold it stops the servos where they are (`{#IIIPDST!…}`), waits, re-plans from the
 * actual pose and carries on; the emergency stop (`ArmLink.stopListeners`) ends it at once.
 * Plain object: the Plan panel samples `state`, `message`, `progress`.
 */
import {
  PlanExecution,
  describeDeviation,
  moveGroup,
  type MotionRobot,
  type MotionSpec,
  type Plan,
} from '@armtwin/motion';
import { encodeGroup, encodeStop } from '@armtwin/protocol';
import type { ArmCommands } from '../link/ArmCommands.ts';
import type { ArmStore } from '../store/ArmStore.ts';
import { hudExecuteOptions } from './executeOptions.ts';

export type RunState = 'idle' | 'running' | 'paused' | 'done' | 'failed' | 'stopped';

/** How often the loop looks at the arm, ms (the plan streams every `stepMs`, 100). */
export const RUN_TICK_MS = 10;

/** What a run needs of the arm link: its groups out, and the emergency stop's call. */
export type PlanLink = Pick<ArmCommands, 'sendGroup' | 'stopListeners'>;

export class PlanRunner {
  state: RunState = 'idle';
  message = '';
  /** 0 … 1 along the plan being run. */
  progress = 0;
  replans = 0;
  /** The plan being run (the re-planned one after a re-plan). */
  plan: Plan | null = null;
  /** Groups streamed, stops sent: for the panel and the tests. */
  sent = 0;
  pauses = 0;
  private exec: PlanExecution | null = null;
  private timer: ReturnType<typeof setInterval> | undefined;
  private link: PlanLink | null = null;
  private lastSent: number[] = [];
  private readonly onStop = () => this.cancel('stopped: emergency stop');
  private readonly listeners = new Set<(plan: Plan) => void>();

  private readonly endListeners = new Set<(state: RunState) => void>();

  /** Called once a run ends (done, failed or stopped), so the ghost's preview of it can go. */
  onEnd(fn: (state: RunState) => void): () => void {
    this.endListeners.add(fn);
    return () => this.endListeners.delete(fn);
  }

  /** Called with each new plan (a re-plan), so the ghost can preview it. */
  onPlan(fn: (plan: Plan) => void): () => void {
    this.listeners.add(fn);
    return () => this.listeners.delete(fn);
  }

  get active(): boolean {
    return this.state === 'running' || this.state === 'paused';
  }

  start(link: PlanLink, store: ArmStore, robot: MotionRobot, plan: Plan, spec: MotionSpec): void {
    this.cancel('');
    const options = hudExecuteOptions(robot, plan, store.expectedStateIntervalMs);
    this.exec = new PlanExecution(robot, plan, spec, options);
    this.plan = plan;
    this.link = link;
    this.state = 'running';
    this.message = 'executing';
    this.progress = 0;
    this.replans = 0;
    this.sent = 0;
    this.pauses = 0;
    this.lastSent = Array.from(store.pwm);
    store.commandedPwm.fill(NaN); // the arm now follows the plan, not this page's last jog
    link.stopListeners.add(this.onStop);
    this.timer = setInterval(() => this.tick(store, robot), RUN_TICK_MS);
  }

  /** Ends a run (`reason` shown; '' = silently, for a new run). */
  cancel(reason: string): void {
    if (!this.exec) return;
    clearInterval(this.timer);
    this.link?.stopListeners.delete(this.onStop);
    this.exec = null;
    this.link = null;
    if (reason) {
      this.state = 'stopped';
      this.message = reason;
      for (const fn of this.endListeners) fn('stopped');
    }
  }

  private finish(state: RunState, message: string): void {
    clearInterval(this.timer);
    this.link?.stopListeners.delete(this.onStop);
    this.exec = null;
    this.link = null;
    this.state = state;
    this.message = message;
    for (const fn of this.endListeners) fn(state);
  }

  private tick(store: ArmStore, robot: MotionRobot): void {
    const exec = this.exec;
    const link = this.link;
    if (!exec || !link) return;
    const actual = Array.from(store.pwm);
    if (actual.some((p) => !Number.isFinite(p)) || actual.length !== robot.ids.length) return;
    const now = performance.now();
    const r = exec.step(now, actual);
    switch (r.kind) {
      case 'move': {
        const frame = moveGroup(robot.ids, this.lastSent, r.pwm, r.ms, robot.table);
        if (frame && link.sendGroup(frame)) this.sent++;
        if (frame) this.lastSent = r.pwm;
        this.state = 'running';
        this.progress = exec.planTime(now) / exec.plan.durationMs;
        return;
      }
      case 'pause':
        link.sendGroup(encodeGroup(robot.ids.map((id) => encodeStop(id))));
        this.lastSent = actual;
        this.pauses++;
        this.state = 'paused';
        this.message = `paused: ${describeDeviation(robot, r.check, exec.options)}; re-planning from the actual pose`;
        return;
      case 'replanned':
        this.replans = r.replans;
        this.plan = r.plan;
        this.state = 'running';
        this.message = `re-planned from the actual pose (${r.replans})`;
        for (const fn of this.listeners) fn(r.plan);
        return;
      case 'done':
        this.progress = 1;
        return this.finish(
          'done',
          `done${this.replans > 0 ? ` after ${this.replans} re-plan${this.replans === 1 ? '' : 's'}` : ''}`,
        );
      case 'failed':
        link.sendGroup(encodeGroup(robot.ids.map((id) => encodeStop(id))));
        return this.finish('failed', `failed (code ${r.code}): ${r.message}`);
      case 'wait':
        this.progress = exec.planTime(now) / exec.plan.durationMs;
        return;
    }
  }
}
