/**
 * Tracking error: what a joint was commanded to do against what it did. Pure.
 *
 * The commanded trajectory: a command (target angle θ, duration ms) issued at t_k moves the
 * joint in a straight line from where it was — its last actual sample at or before t_k —
 * to θ, arriving at t_k + ms, then holds θ until the next command (this is how the servo
 * executes `#IIIPppppTtttt!`). With no actual sample before t_k the move is a step to θ.
 *
 * Each actual sample in [start, stop) with a command at or before it is compared with the
 * commanded trajectory interpolated at the sample's time; samples before the first known
 * command are not scored. Reported like seed 001's tables: mean and maximum absolute error.
 */
import type { TrackingJoint } from '@armtwin/api';
import type { Sample } from './alarms.ts';

export interface Command {
  /** Epoch ms. */
  t: number;
  /** Target angle, degrees. */
  angle: number;
  /** Move duration, ms. */
  ms: number;
}

/** One joint's figures, as `/history/tracking` answers them. */
export type TrackingStats = TrackingJoint;

/** The commanded angle at `t`, moving from `from` at `cmd.t` to `cmd.angle` over `cmd.ms`. */
export function commandedAt(cmd: Command, from: number, t: number): number {
  if (cmd.ms <= 0 || t >= cmd.t + cmd.ms) return cmd.angle;
  const f = Math.max(0, (t - cmd.t) / cmd.ms);
  return from + (cmd.angle - from) * f;
}

/**
 * Error figures for one joint. `commands` and `actual` sorted by time; only samples with
 * startMs ≤ t < stopMs are scored (earlier ones still give a command its starting point).
 */
export function trackingStats(
  id: string,
  commands: readonly Command[],
  actual: readonly Sample[],
  startMs: number,
  stopMs: number,
): TrackingStats {
  let n = 0;
  let sum = 0;
  let max = -1;
  let maxAt: number | null = null;
  let k = -1; // index of the command in force
  let from = 0; // where that command's move started
  let lastActual: Sample | undefined; // the last sample before the current one
  for (const s of actual) {
    while (k + 1 < commands.length && commands[k + 1]!.t <= s.t) {
      k++;
      const c = commands[k]!;
      // The position the move starts from: the latest sample at or before the command.
      from = lastActual && lastActual.t <= c.t ? lastActual.v : c.angle;
      if (s.t === c.t) from = s.v;
    }
    lastActual = s;
    if (k < 0 || s.t < startMs || s.t >= stopMs) continue;
    const err = Math.abs(s.v - commandedAt(commands[k]!, from, s.t));
    n++;
    sum += err;
    if (err > max) {
      max = err;
      maxAt = s.t;
    }
  }
  return { id, samples: n, meanAbsError: n ? sum / n : null, maxAbsError: n ? max : null, maxAt };
}
