/**
 * Motion feedback (`arm/{id}/feedback`, JSON): one message per change of a request's state.
 * Every message has `id`, `status`, `code` and `message`; the rest depends on the status.
 */
import type { PlanOutcome } from './motion.ts';
import { planEnd, type MotionMode, type Plan } from './plan.ts';

export type MotionStatus = 'planned' | 'unreachable' | 'executing' | 'done' | 'failed' | 'stopped';

export interface MotionFeedback {
  /** The request's id (null when the request had none that could be read). */
  id: string | null;
  status: MotionStatus;
  /** 0, an IK code (unreachable), or 20–23 (`MOTION_CODES`). */
  code: number;
  message: string;
  /** Sender's time, Unix epoch ms. */
  t?: number;
  /** Plan summary (planned, executing): mode, duration, number of samples, end pose (µs by servo id). */
  mode?: MotionMode;
  durationMs?: number;
  samples?: number;
  end?: Record<string, number>;
  /** unreachable: the target (index) and the Cartesian step (1-based) that failed. */
  target?: number;
  step?: number;
  /** failed (invalid request): the field at fault, e.g. `targets[1].x`. */
  field?: string;
  /** executing: what happened (`started`, `paused`, `replanned`). */
  event?: 'started' | 'paused' | 'replanned';
  /** Re-plans so far in this execution. */
  replans?: number;
  /** paused: the servo furthest off the plan, its deviation (deg or mm). */
  servo?: string;
  deviation?: number;
}

/** Plan summary fields of a feedback message. */
export function planSummary(
  plan: Plan,
): Pick<MotionFeedback, 'mode' | 'durationMs' | 'samples' | 'end'> {
  const end: Record<string, number> = {};
  const last = planEnd(plan);
  plan.ids.forEach((id, i) => (end[String(id).padStart(3, '0')] = Math.round(last[i]!)));
  return {
    mode: plan.mode,
    durationMs: Math.round(plan.durationMs),
    samples: plan.samples.length,
    end,
  };
}

/** The feedback of a planning outcome (planned / unreachable / failed). */
export function outcomeFeedback(id: string | null, o: PlanOutcome): MotionFeedback {
  const f: MotionFeedback = { id, status: o.status, code: o.code, message: o.message };
  if (o.status === 'planned') Object.assign(f, planSummary(o.plan));
  else if (o.status === 'unreachable') {
    f.target = o.target;
    if (o.step !== undefined) f.step = o.step;
  } else f.field = o.field;
  return f;
}
