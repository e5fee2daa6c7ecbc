/**
 * Streaming a plan as wire frames: one `{#IIIPppppTtttt!…}` group every `stepMs`, each moving
 * the servos to the plan's pose one step later in that step's time, so the arm follows the plan
 * while the next group is on its way. Pulses are rounded here (and only here); a servo whose
 * rounded pulse does not change is left out of its group, and a step where none changes sends
 * nothing. A servo that speaks angles (profile `"units": "angle"`) gets `#IIIA±ddd.ddTtttt!`
 * instead, its exact pulse-equivalent turned into its angle and rounded to the wire's 0.01°.
 */
import type { ServoTableEntry } from '@armtwin/robot';
import {
  MOVE_MS_MAX,
  angleFromPwm,
  encodeAngleMove,
  encodeGroup,
  encodeMove,
} from '@armtwin/protocol';
import { samplePlan, type Plan } from './plan.ts';

/** Per servo (plan order) what the wire frames need: `robot.table`. Absent: pulses for all. */
export type WireUnits = readonly Pick<ServoTableEntry, 'units' | 'polarity'>[];

/** An angle servo's angle of an exact pulse-equivalent, in the wire's hundredths of a degree. */
const wireAngle = (pwm: number, polarity: 1 | -1) =>
  Math.round(angleFromPwm(pwm, polarity) * 100) / 100;

export interface TimedFrame {
  /** When to send it, ms from the start of the execution. */
  at: number;
  /** The move time inside it, ms. */
  ms: number;
  /** `{#000P1500T0020!…}`. */
  frame: string;
}

/**
 * The moves of one step: servos whose rounded pulse (or, for an angle servo, rounded angle)
 * changes from `prev`, to `pwm` in `ms`.
 */
export function moveGroup(
  ids: readonly number[],
  prev: readonly number[],
  pwm: readonly number[],
  ms: number,
  units?: WireUnits,
): string {
  const moves: string[] = [];
  for (let i = 0; i < ids.length; i++) {
    const u = units?.[i];
    if (u?.units === 'angle') {
      const deg = wireAngle(pwm[i]!, u.polarity);
      if (deg !== wireAngle(prev[i]!, u.polarity)) moves.push(encodeAngleMove(ids[i]!, deg, ms));
      continue;
    }
    const p = Math.round(pwm[i]!);
    if (p !== Math.round(prev[i]!)) moves.push(encodeMove(ids[i]!, p, ms));
  }
  return moves.length === 0 ? '' : encodeGroup(moves);
}

/** The plan as timed groups to stream, `stepMs` (1–9999) apart; `units`: `robot.table`. */
export function toMoveFrames(plan: Plan, stepMs: number, units?: WireUnits): TimedFrame[] {
  if (!(stepMs >= 1 && stepMs <= MOVE_MS_MAX))
    throw new RangeError(`stepMs must be in 1–${MOVE_MS_MAX}`);
  const out: TimedFrame[] = [];
  let prev = samplePlan(plan, 0);
  for (let at = 0; at < plan.durationMs; at += stepMs) {
    const next = Math.min(at + stepMs, plan.durationMs);
    const ms = Math.min(MOVE_MS_MAX, Math.ceil(next - at));
    const pwm = samplePlan(plan, next);
    const frame = moveGroup(plan.ids, prev, pwm, ms, units);
    if (frame) {
      out.push({ at, ms, frame });
      prev = pwm;
    }
  }
  return out;
}
