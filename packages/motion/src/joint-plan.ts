/**
 * Joint-space plans: every axis goes straight (in pulses) from one target to the next, all
 * starting and finishing together. The slowest axis at its speed limit (× `speed`) sets the
 * segment's time; the others are slowed to match. `linear`: constant speed. `trapezoid`: each
 * axis ramps up at its own acceleration (top speed in `accelMs`), cruises and ramps down, its
 * cruise speed chosen so it arrives exactly when the slowest axis does. Neither ever exceeds a
 * speed limit, and every pulse stays between the segment's ends (so within the limits).
 */
import { DEFAULT_PLAN_OPTIONS, type PlanOptions } from './options.ts';
import { joinPlans, type Plan, type PlanSample } from './plan.ts';
import type { MotionRobot } from './robot.ts';

/** Top speed of servo i under `speed`, µs per ms. */
export const topSpeed = (robot: MotionRobot, i: number, speed: number): number =>
  (robot.table[i]!.maxSpeedPwmPerS / 1000) * speed;

/** Shortest time (ms) a trapezoid covers d at top speed v and acceleration a. */
function trapezoidTime(d: number, v: number, a: number): number {
  return d >= (v * v) / a ? d / v + v / a : 2 * Math.sqrt(d / a);
}

/** Distance covered at time t by a trapezoid of cruise speed w, acceleration a, total time T. */
function trapezoidAt(t: number, d: number, w: number, a: number, T: number): number {
  if (t <= 0) return 0;
  if (t >= T) return d;
  const ramp = w / a;
  if (t < ramp) return 0.5 * a * t * t;
  if (t <= T - ramp) return 0.5 * a * ramp * ramp + w * (t - ramp);
  const r = T - t;
  return d - 0.5 * a * r * r;
}

/**
 * A target's timing (a taught plan, `teach.ts`): reach it in `durationMs` (or as soon as each
 * servo's own speed limit allows, if that is longer: `speed` does not slow a timed segment),
 * then hold it `holdMs`.
 */
export interface TargetTiming {
  durationMs?: number;
  holdMs?: number;
}

/**
 * One segment from `from` to `to` (both complete pulse vectors). With `durationMs`, the segment
 * takes that long (at least the time the servos' limits need at full speed) instead of the
 * time `speed` gives; a segment that does not move then holds still for that long.
 */
export function planJointSegment(
  robot: MotionRobot,
  from: readonly number[],
  to: readonly number[],
  options: Partial<PlanOptions> = {},
  durationMs?: number,
): Plan {
  const timed = durationMs !== undefined && Number.isFinite(durationMs);
  const o = { ...DEFAULT_PLAN_OPTIONS, ...options, ...(timed ? { speed: 1 } : {}) };
  const n = from.length;
  const d: number[] = [];
  const v: number[] = [];
  const a: number[] = [];
  let T = 0;
  for (let i = 0; i < n; i++) {
    d[i] = Math.abs(to[i]! - from[i]!);
    v[i] = topSpeed(robot, i, o.speed);
    a[i] = v[i]! / Math.max(1e-6, o.accelMs);
    if (d[i]! === 0) continue;
    T = Math.max(T, o.profile === 'linear' ? d[i]! / v[i]! : trapezoidTime(d[i]!, v[i]!, a[i]!));
  }
  if (timed) T = Math.max(T, durationMs);
  const ids = robot.ids;
  if (!(T > 0))
    return {
      mode: 'joint',
      ids,
      samples: [{ t: 0, pwm: [...from] }],
      durationMs: 0,
      targetTimes: [0],
    };
  // Cruise speed of each axis so that it arrives at T.
  const w = d.map((di, i) => {
    if (o.profile === 'linear' || di === 0) return di / T;
    const ai = a[i]!;
    return Math.min(v[i]!, (ai * T - Math.sqrt(Math.max(0, ai * ai * T * T - 4 * ai * di))) / 2);
  });
  const at = (t: number): number[] =>
    from.map((p, i) => {
      const di = d[i]!;
      if (di === 0) return p;
      const s =
        o.profile === 'linear' ? (di * Math.min(t, T)) / T : trapezoidAt(t, di, w[i]!, a[i]!, T);
      const q = to[i]! >= p ? p + s : p - s;
      return Math.min(Math.max(q, Math.min(p, to[i]!)), Math.max(p, to[i]!)); // never past either end
    });
  const samples: PlanSample[] = [];
  const steps = Math.max(1, Math.ceil(T / o.stepMs));
  for (let k = 0; k < steps; k++) {
    const t = k * o.stepMs;
    // A sample a hair before T would make a step so short that rounding shows as overspeed.
    if (k > 0 && T - t < o.stepMs * 1e-3) break;
    samples.push({ t, pwm: at(t) });
  }
  samples.push({ t: T, pwm: [...to] });
  return { mode: 'joint', ids, samples, durationMs: T, targetTimes: [T] };
}

/**
 * A joint plan through `targets` in turn, starting at `from`. A target's NaN entries keep that
 * servo where the previous target left it. `timing[k]` (optional) times target k; a hold comes
 * after the target is reached (its target time is the arrival).
 */
export function planJoint(
  robot: MotionRobot,
  from: readonly number[],
  targets: readonly (readonly number[])[],
  options: Partial<PlanOptions> = {},
  timing: readonly (TargetTiming | undefined)[] = [],
): Plan {
  const parts: Plan[] = [];
  let at = [...from];
  for (const [k, target] of targets.entries()) {
    const to = at.map((p, i) => (Number.isNaN(target[i]) ? p : target[i]!));
    const tk = timing[k];
    parts.push(planJointSegment(robot, at, to, options, tk?.durationMs));
    const hold = tk?.holdMs ?? 0;
    if (hold > 0)
      parts.push({ ...planJointSegment(robot, to, to, options, hold), targetTimes: [] });
    at = to;
  }
  return joinPlans('joint', robot.ids, parts);
}
