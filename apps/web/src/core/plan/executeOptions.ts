/**
 * Pose checking from the HUD. The arm checks itself against the plan with no delay; the HUD sees
 * the arm one state report (plus a streamed step and the network) late, so at speed v a servo
 * looks `v · lag` behind the plan while exactly on it. The HUD's thresholds are the arm's
 * (`DEFAULT_EXECUTE_OPTIONS`: 5°, 20 mm) plus that allowance, from the plan's fastest servo.
 * Pure.
 */
import { servoFromPwm } from '@armtwin/robot';
import {
  DEFAULT_EXECUTE_OPTIONS,
  type ExecuteOptions,
  type MotionRobot,
  type Plan,
} from '@armtwin/motion';

export interface HudExecuteOptions {
  /**
   * A move is streamed every this many ms, each to the plan's pose one step later. The page's
   * timers share the main thread with rendering (software WebGL draws a frame in ~100 ms), and a
   * late step makes the arm wait (PlanExecution), so the step is what a slow page can keep up
   * with; 10 groups/s also leaves the controller's 50 commands/s to jogs and pings.
   */
  stepMs: number;
  /** Extra lag allowed beyond the report interval and the step (network, rendering), ms. */
  marginMs: number;
}

export const DEFAULT_HUD_EXECUTE_OPTIONS: HudExecuteOptions = { stepMs: 100, marginMs: 60 };

/** Fastest speed of any revolute (°/s) and any prismatic (mm/s) servo in the plan. */
export function planPeakSpeeds(robot: MotionRobot, plan: Plan): { deg: number; mm: number } {
  const servos = robot.profile.servos;
  let deg = 0;
  let mm = 0;
  const s = plan.samples;
  for (let k = 1; k < s.length; k++) {
    const dt = (s[k]!.t - s[k - 1]!.t) / 1000;
    if (!(dt > 0)) continue;
    servos.forEach((servo, i) => {
      const v =
        Math.abs(servoFromPwm(servo, s[k]!.pwm[i]!) - servoFromPwm(servo, s[k - 1]!.pwm[i]!)) / dt;
      if (servo.type === 'revolute') deg = Math.max(deg, v);
      else mm = Math.max(mm, v);
    });
  }
  return { deg, mm };
}

/** ExecuteOptions for `PlanExecution` run by the HUD, given the state report interval (ms). */
export function hudExecuteOptions(
  robot: MotionRobot,
  plan: Plan,
  reportIntervalMs: number,
  o: HudExecuteOptions = DEFAULT_HUD_EXECUTE_OPTIONS,
): Partial<ExecuteOptions> {
  const lagS =
    ((Number.isFinite(reportIntervalMs) ? reportIntervalMs : 100) + o.stepMs + o.marginMs) / 1000;
  const peak = planPeakSpeeds(robot, plan);
  return {
    stepMs: o.stepMs,
    thresholdDeg: DEFAULT_EXECUTE_OPTIONS.thresholdDeg + peak.deg * lagS,
    thresholdMm: DEFAULT_EXECUTE_OPTIONS.thresholdMm + peak.mm * lagS,
  };
}
