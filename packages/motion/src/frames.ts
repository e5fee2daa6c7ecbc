/**
 * Streaming a plan as wire frames: one `{#IIIPppppTtttt!…}` group every `stepMs`, each moving
 * the servos to the plan's pose one step later in that step's time, so the arm follows the plan
 * while the next group is on its way. Pulses are rounded here (and only here); a servo whose
 * rounded pulse does not change is left out of its group, and a step where none changes sends
 * nothing.
 */
import { MOVE_MS_MAX, encodeGroup, encodeMove } from '@armtwin/protocol';
import { samplePlan, type Plan } from './plan.ts';

export interface TimedFrame {
  /** When to send it, ms from the start of the execution. */
  at: number;
  /** The move time inside it, ms. */
  ms: number;
  /** `{#000P1500T0020!…}`. */
  frame: string;
}

/** The moves of one step: servos whose rounded pulse changes from `prev`, to `pwm` in `ms`. */
export function moveGroup(
  ids: readonly number[],
  prev: readonly number[],
  pwm: readonly number[],
  ms: number,
): string {
  const moves: string[] = [];
  for (let i = 0; i < ids.length; i++) {
    const p = Math.round(pwm[i]!);
    if (p !== Math.round(prev[i]!)) moves.push(encodeMove(ids[i]!, p, ms));
  }
  return moves.length === 0 ? '' : encodeGroup(moves);
}

/** The plan as timed groups to stream, `stepMs` (1–9999) apart. */
export function toMoveFrames(plan: Plan, stepMs: number): TimedFrame[] {
  if (!(stepMs >= 1 && stepMs <= MOVE_MS_MAX))
    throw new RangeError(`stepMs must be in 1–${MOVE_MS_MAX}`);
  const out: TimedFrame[] = [];
  let prev = samplePlan(plan, 0);
  for (let at = 0; at < plan.durationMs; at += stepMs) {
    const next = Math.min(at + stepMs, plan.durationMs);
    const ms = Math.min(MOVE_MS_MAX, Math.ceil(next - at));
    const pwm = samplePlan(plan, next);
    const frame = moveGroup(plan.ids, prev, pwm, ms);
    if (frame) {
      out.push({ at, ms, frame });
      prev = pwm;
    }
  }
  return out;
}
