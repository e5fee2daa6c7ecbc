/**
 * A trajectory_msgs/JointTrajectory (as ./wire.ts carries it) as armtwin's timed move frames:
 * from the pose the arm reports now, through each point at its time_from_start, linear in pulses
 * between them, streamed as `{#IIIPppppTtttt!…}` groups (`#IIIA±ddd.ddTtttt!` for angle servos)
 * `stepMs` apart: the frames every controller takes, which the controller checks (lease, limits,
 * floor, zones) as any move. Joints the trajectory does not name stay where they are. An empty
 * trajectory is a stop, as joint_trajectory_controller holds position on one.
 *
 * Refused whole, with a reason: a joint the profile does not have, a point without every
 * position, times that do not increase, a position no frame can carry. Pure.
 */
import { servoFromJoint, type Profile } from '@armtwin/robot';
import {
  exactPwmFromServo,
  toMoveFrames,
  type Plan,
  type PlanSample,
  type TimedFrame,
  type WireUnits,
} from '@armtwin/motion';
import { ANGLE_DEG_MAX, PWM_MAX, PWM_MIN, angleFromPwm } from '@armtwin/protocol';
import type { JointTrajectoryMsg } from './wire.ts';

export const TRAJECTORY_REFUSALS = [
  'unknown-joint',
  'bad-point',
  'bad-time',
  'out-of-range',
  'no-state',
] as const;
export type TrajectoryRefusal = (typeof TRAJECTORY_REFUSALS)[number];

/** Longest trajectory taken, ms (its frames are made at once). */
export const MAX_TRAJECTORY_MS = 600_000;

export type TrajectoryFrames =
  | { kind: 'move'; frames: TimedFrame[]; durationMs: number }
  | { kind: 'stop'; ids: number[] }
  | { kind: 'refused'; reason: TrajectoryRefusal; message: string };

const refuse = (reason: TrajectoryRefusal, message: string): TrajectoryFrames => ({
  kind: 'refused',
  reason,
  message,
});

/** Whether a wire frame can carry this exact pulse for servo i. */
function encodable(units: WireUnits[number], pwm: number): boolean {
  if (units.units === 'angle') return Math.abs(angleFromPwm(pwm, units.polarity)) <= ANGLE_DEG_MAX;
  const p = Math.round(pwm);
  return p >= PWM_MIN && p <= PWM_MAX;
}

/**
 * The frames of `traj` from the pose `currentPwm` (profile servo order, NaN = not reported).
 * `units`: per servo, what its frames carry (`robot.table`).
 */
export function trajectoryFrames(
  profile: Profile,
  units: WireUnits,
  currentPwm: readonly number[],
  traj: JointTrajectoryMsg,
  stepMs: number,
): TrajectoryFrames {
  const servos = profile.servos;
  const index: number[] = [];
  for (const name of traj.joint_names) {
    const i = servos.findIndex((s) => s.joint === name);
    if (i < 0)
      return refuse(
        'unknown-joint',
        `joint ${name} is not in profile ${profile.name} (${servos.map((s) => s.joint).join(', ')})`,
      );
    index.push(i);
  }
  if (traj.points.length === 0)
    return {
      kind: 'stop',
      ids: (index.length ? index : servos.map((_, i) => i)).map((i) => servos[i]!.id),
    };
  if (currentPwm.some((p) => !Number.isFinite(p)))
    return refuse('no-state', 'the arm has not reported every servo yet');
  const samples: PlanSample[] = [{ t: 0, pwm: [...currentPwm] }];
  for (const [k, p] of traj.points.entries()) {
    if (p.positions.length !== index.length || !p.positions.every(Number.isFinite))
      return refuse(
        'bad-point',
        `point ${k} has ${p.positions.length} positions for ${index.length} joints`,
      );
    const t = p.time_from_start_ms;
    const last = samples[samples.length - 1]!;
    if (!(t > last.t) || t > MAX_TRAJECTORY_MS)
      return refuse(
        'bad-time',
        `point ${k}: time_from_start ${t} ms must be after the previous point's (${last.t} ms) and at most ${MAX_TRAJECTORY_MS} ms`,
      );
    const pwm = [...last.pwm];
    for (const [j, i] of index.entries()) {
      const servo = servos[i]!;
      pwm[i] = exactPwmFromServo(servo, servoFromJoint(servo, p.positions[j]!));
      if (!encodable(units[i]!, pwm[i]!))
        return refuse(
          'out-of-range',
          `point ${k}: joint ${servo.joint} at ${p.positions[j]} is beyond what servo ${servo.key} can be sent`,
        );
    }
    samples.push({ t, pwm });
  }
  const durationMs = samples[samples.length - 1]!.t;
  const plan: Plan = {
    mode: 'joint',
    ids: servos.map((s) => s.id),
    samples,
    durationMs,
    targetTimes: samples.slice(1).map((s) => s.t),
  };
  return { kind: 'move', frames: toMoveFrames(plan, stepMs, units), durationMs };
}
