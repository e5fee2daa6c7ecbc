/**
 * A plan: timed samples of every servo's pulse, from the pose the arm is in (t = 0) to the last
 * target. Pulses are exact (fractional µs) and always within the servo's limits; between two
 * samples the motion is linear in pulses. `samplePlan` reads it at any time.
 */

export type MotionMode = 'joint' | 'cartesian';

export interface PlanSample {
  /** Time from the start of the plan, ms. */
  readonly t: number;
  /** Pulse of every servo (µs, exact), in profile servo order. */
  readonly pwm: readonly number[];
}

export interface Plan {
  readonly mode: MotionMode;
  /** Wire ids of the servos, in the order of each sample's `pwm`. */
  readonly ids: readonly number[];
  /** At least one sample; `samples[0].t` is 0 and times increase strictly after it. */
  readonly samples: readonly PlanSample[];
  /** Time of the last sample, ms. */
  readonly durationMs: number;
  /** Time (ms) at which each target is reached, in target order. */
  readonly targetTimes: readonly number[];
}

/** Pulses of the plan at time t (ms from its start; clamped to the plan), into `out`. */
export function samplePlan(plan: Plan, t: number, out: number[] = []): number[] {
  const s = plan.samples;
  const n = plan.ids.length;
  out.length = n;
  if (!(t > 0) || s.length === 1) {
    for (let i = 0; i < n; i++) out[i] = s[0]!.pwm[i]!;
    return out;
  }
  if (t >= plan.durationMs) {
    const last = s[s.length - 1]!;
    for (let i = 0; i < n; i++) out[i] = last.pwm[i]!;
    return out;
  }
  // Binary search for the last sample at or before t.
  let lo = 0,
    hi = s.length - 1;
  while (hi - lo > 1) {
    const mid = (lo + hi) >> 1;
    if (s[mid]!.t <= t) lo = mid;
    else hi = mid;
  }
  const a = s[lo]!,
    b = s[hi]!;
  const u = b.t > a.t ? (t - a.t) / (b.t - a.t) : 1;
  for (let i = 0; i < n; i++) out[i] = a.pwm[i]! + (b.pwm[i]! - a.pwm[i]!) * u;
  return out;
}

/** The pulses at the end of the plan. */
export const planEnd = (plan: Plan): readonly number[] =>
  plan.samples[plan.samples.length - 1]!.pwm;

/** Index of the first target not yet reached at time t (targets.length when all are). */
export function nextTargetIndex(plan: Plan, t: number): number {
  const i = plan.targetTimes.findIndex((tt) => tt > t);
  return i < 0 ? plan.targetTimes.length : i;
}

/** Concatenates plans run one after the other (each starting where the previous ended). */
export function joinPlans(mode: MotionMode, ids: readonly number[], parts: readonly Plan[]): Plan {
  const samples: PlanSample[] = [];
  const targetTimes: number[] = [];
  let offset = 0;
  for (const p of parts) {
    const from = samples.length === 0 ? 0 : 1; // the first sample repeats the previous end
    for (let k = from; k < p.samples.length; k++) {
      const s = p.samples[k]!;
      samples.push({ t: s.t + offset, pwm: s.pwm });
    }
    for (const tt of p.targetTimes) targetTimes.push(tt + offset);
    offset += p.durationMs;
  }
  return { mode, ids, samples, durationMs: offset, targetTimes };
}
