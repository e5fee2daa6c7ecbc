/**
 * Pose checking (seed 001's Pose Checking Algorithm): compare the pose the arm should be in
 * (the plan at time t: θ_virtual) with the pose it reports (θ_physical), joint by joint. Any
 * joint off by more than the threshold means: hold (θ_next ← where it is) and re-plan from the
 * actual pose; otherwise carry on with the next pose. Deviations are in servo units: degrees
 * for a revolute servo, mm for a prismatic axis.
 */
import { servoFromPwm } from '@armtwin/robot';
import { DEFAULT_EXECUTE_OPTIONS, type ExecuteOptions } from './options.ts';
import { samplePlan, type Plan } from './plan.ts';
import type { MotionRobot } from './robot.ts';

export interface PoseCheck {
  /** True when every servo is within its threshold. */
  ok: boolean;
  /** |actual − planned| per servo, degrees or mm, profile order. */
  deviation: number[];
  /** Index of the servo furthest over its threshold (or the largest deviation when ok). */
  worst: number;
  /** The planned pulses at t. */
  expected: number[];
}

/** Deviation of `actual` (pulses, profile order) from the plan at time t (ms from its start). */
export function checkPose(
  robot: MotionRobot,
  plan: Plan,
  t: number,
  actual: ArrayLike<number>,
  options: Partial<Pick<ExecuteOptions, 'thresholdDeg' | 'thresholdMm'>> = {},
): PoseCheck {
  const o = { ...DEFAULT_EXECUTE_OPTIONS, ...options };
  const expected = samplePlan(plan, t);
  const servos = robot.profile.servos;
  let worst = 0,
    worstRatio = -Infinity,
    ok = true;
  const deviation = expected.map((p, i) => {
    const s = servos[i]!;
    const d = Math.abs(servoFromPwm(s, actual[i]!) - servoFromPwm(s, p));
    const limit = s.type === 'revolute' ? o.thresholdDeg : o.thresholdMm;
    const ratio = Number.isFinite(d) ? d / limit : Infinity;
    if (ratio > 1) ok = false;
    if (ratio > worstRatio) {
      worstRatio = ratio;
      worst = i;
    }
    return d;
  });
  return { ok, deviation, worst, expected };
}
