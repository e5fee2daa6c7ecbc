/**
 * From a validated request to a plan: targets resolved against the profile (named poses, servo
 * values, tip targets), then a joint or Cartesian plan from the pose the arm is in. The
 * outcome says `planned`, `unreachable` (with the IK code, or 21 for a servo limit, and the
 * target and step) or `failed` (20, a field the profile does not know). `replanFrom` plans the
 * targets not yet reached from where the arm actually is (pose checking's re-plan).
 */
import { servoFromPwm, servoWithinLimits } from '@armtwin/robot';
import { planCartesian, type CartesianWaypoint } from './cartesian-plan.ts';
import {
  CODE_BELOW_FLOOR,
  CODE_INVALID,
  CODE_IN_ZONE,
  CODE_SELF_COLLISION,
  CODE_SERVO_LIMIT,
  motionCodeMessage,
} from './codes.ts';
import { planBelowFloor } from './floor.ts';
import { planJoint, type TargetTiming } from './joint-plan.ts';
import { planInZone } from './zones/zones.ts';
import type { PlanOptions } from './options.ts';
import { nextTargetIndex, type MotionMode, type Plan } from './plan.ts';
import type { MotionRequest, RequestTarget } from './request.ts';
import { exactPwmFromServo, solveTip, tipPose, type MotionRobot, type TipTarget } from './robot.ts';

/**
 * A target in the arm's terms: pulses (NaN = leave the servo) or a tip target. A joint target
 * may be timed (a taught plan: `TargetTiming`; joint mode only, a Cartesian plan ignores it).
 */
export type ResolvedTarget =
  ({ kind: 'joint'; pwm: number[] } & TargetTiming) | { kind: 'tip'; tip: TipTarget };

/** What a plan was made from, kept so it can be re-planned from another pose. */
export interface MotionSpec {
  readonly mode: MotionMode;
  readonly targets: readonly ResolvedTarget[];
  readonly options: Partial<PlanOptions>;
}

export type PlanOutcome =
  | { status: 'planned'; code: 0; plan: Plan; spec: MotionSpec; message: string }
  | {
      status: 'unreachable';
      code: number;
      message: string;
      target: number;
      step?: number;
    }
  | { status: 'failed'; code: typeof CODE_INVALID; message: string; field: string };

type Resolved = { ok: true; target: ResolvedTarget } | Exclude<PlanOutcome, { status: 'planned' }>;

function resolveTarget(
  robot: MotionRobot,
  t: RequestTarget,
  path: string,
  index: number,
): Resolved {
  const { profile } = robot;
  const servos = profile.servos;
  if (typeof t === 'string') {
    const values = profile.poses[t];
    if (!values) {
      const names = Object.keys(profile.poses).join(', ');
      return {
        status: 'failed',
        code: CODE_INVALID,
        field: path,
        message: `${path}: no pose "${t}" on ${profile.name} (poses: ${names})`,
      };
    }
    const pwm = servos.map((s, i) =>
      Number.isNaN(values[i]) ? NaN : exactPwmFromServo(s, values[i]!),
    );
    return { ok: true, target: { kind: 'joint', pwm } };
  }
  if ('servos' in t) {
    const unit = t.unit ?? 'us';
    const pwm = new Array<number>(servos.length).fill(NaN);
    for (const [key, v] of Object.entries(t.servos)) {
      const i = servos.findIndex((s) => s.key === key);
      const field = `${path}.servos.${key}`;
      if (i < 0)
        return {
          status: 'failed',
          code: CODE_INVALID,
          field,
          message: `${field}: ${profile.name} has no servo ${key}`,
        };
      const s = servos[i]!;
      const value = unit === 'us' ? servoFromPwm(s, v) : unit === 'joint' ? v - s.offset : v;
      const { minPwm, maxPwm } = robot.table[i]!;
      const ok = unit === 'us' ? v >= minPwm && v <= maxPwm : servoWithinLimits(s, value);
      if (!ok) {
        const u = unit === 'us' ? 'µs' : s.type === 'revolute' ? '°' : 'mm';
        return {
          status: 'unreachable',
          code: CODE_SERVO_LIMIT,
          target: index,
          message: `${field}: ${v} ${u} is outside the servo's limits (${minPwm}–${maxPwm} µs)`,
        };
      }
      pwm[i] = unit === 'us' ? v : Math.min(maxPwm, Math.max(minPwm, exactPwmFromServo(s, value)));
    }
    return { ok: true, target: { kind: 'joint', pwm } };
  }
  return { ok: true, target: { kind: 'tip', tip: { ...t } } };
}

const fill = (target: readonly number[], at: readonly number[]) =>
  at.map((p, i) => (Number.isNaN(target[i]) ? p : target[i]!));

/** Plans resolved targets from `from` (the pulses the arm is at). */
export function planSpec(
  robot: MotionRobot,
  spec: MotionSpec,
  from: readonly number[],
): PlanOutcome {
  const n = robot.ids.length;
  if (from.length !== n || from.some((v) => !Number.isFinite(v)))
    return {
      status: 'failed',
      code: CODE_INVALID,
      field: '(pose)',
      message: `the arm's pose is not known (${n} pulses needed)`,
    };
  let at = [...from];
  if (spec.mode === 'joint') {
    const joints: number[][] = [];
    const timing: (TargetTiming | undefined)[] = [];
    for (const [i, t] of spec.targets.entries()) {
      timing.push(t.kind === 'joint' ? { durationMs: t.durationMs, holdMs: t.holdMs } : undefined);
      let pwm: number[];
      if (t.kind === 'joint') pwm = t.pwm;
      else {
        const r = solveTip(robot, t.tip, at);
        if (r.code !== 0)
          return {
            status: 'unreachable',
            code: r.code,
            target: i,
            message: `targets[${i}]: ${motionCodeMessage(r.code)}`,
          };
        pwm = r.pwm;
      }
      at = fill(pwm, at);
      joints.push(pwm);
    }
    return planned(robot, planJoint(robot, from, joints, spec.options, timing), spec);
  }
  const waypoints: CartesianWaypoint[] = spec.targets.map((t) => {
    if (t.kind === 'tip') return { tip: t.tip };
    const end = fill(t.pwm, at);
    at = end;
    return { tip: tipPose(robot, end), others: t.pwm };
  });
  const r = planCartesian(robot, from, waypoints, spec.options, motionCodeMessage);
  if (!r.ok) {
    const out: PlanOutcome = {
      status: 'unreachable',
      code: r.code,
      target: r.target,
      message: r.message,
    };
    if (r.step !== undefined) out.step = r.step;
    return out;
  }
  return planned(robot, r.plan, spec);
}

/**
 * A plan that stays above the floor and out of every keep-out zone (its path between samples
 * included) is `planned`; one that dips below the floor is refused (24), one that enters a zone
 * (25) or folds onto itself (26) too, naming the target it was heading for.
 */
function planned(robot: MotionRobot, plan: Plan, spec: MotionSpec): PlanOutcome {
  const low = planBelowFloor(robot, plan);
  const hit = low ? null : planInZone(robot, plan);
  if (!low && !hit) return { status: 'planned', code: 0, plan, spec, message: summary(plan, spec) };
  const t = plan.samples[(low ?? hit)!.sample]!.t;
  const target = Math.max(
    0,
    plan.targetTimes.findIndex((tt) => tt >= t),
  );
  const code = low
    ? CODE_BELOW_FLOOR
    : hit!.check.kind === 'zone'
      ? CODE_IN_ZONE
      : CODE_SELF_COLLISION;
  return {
    status: 'unreachable',
    code,
    target,
    message: `targets[${target}]: ${(low ?? hit)!.check.message}`,
  };
}

function summary(plan: Plan, spec: MotionSpec): string {
  const n = spec.targets.length;
  return `${spec.mode} plan: ${n} target${n === 1 ? '' : 's'}, ${Math.round(plan.durationMs)} ms, ${plan.samples.length} samples`;
}

/** Resolves a validated request against the arm and plans it from `from`. */
export function planRequest(
  robot: MotionRobot,
  request: MotionRequest,
  from: readonly number[],
  options: Partial<PlanOptions> = {},
): PlanOutcome {
  const targets: ResolvedTarget[] = [];
  for (const [i, t] of request.targets.entries()) {
    const r = resolveTarget(robot, t, `targets[${i}]`, i);
    if (!('ok' in r)) return r;
    targets.push(r.target);
  }
  const o: Partial<PlanOptions> = { ...options };
  if (request.speed !== undefined) o.speed = request.speed;
  if (request.linearSpeed !== undefined) o.linearSpeed = request.linearSpeed;
  return planSpec(robot, { mode: request.mode, targets, options: o }, from);
}

/**
 * Pose checking's re-plan: the targets not yet reached at plan time t (the last one, if all
 * were), planned from the pulses the arm is actually at.
 */
export function replanFrom(
  robot: MotionRobot,
  spec: MotionSpec,
  plan: Plan,
  t: number,
  actual: readonly number[],
): PlanOutcome {
  const next = Math.min(nextTargetIndex(plan, t), spec.targets.length - 1);
  return planSpec(robot, { ...spec, targets: spec.targets.slice(next) }, actual);
}
