/**
 * What a Foxglove client may publish to an arm, as the arm's timed move frames:
 *
 * - `/{arm}/joint_trajectory`: a trajectory_msgs/JointTrajectory in JSON (`joint_names`,
 *   `points[].positions` in rad or m, `time_from_start` as `{sec, nsec}` or
 *   `time_from_start_ms`), as a ROS tool or a Foxglove panel writes it; no points = a stop.
 * - `/{arm}/jog`: `{"joint": NAME, "delta": rad, "ms": 300}`: that joint `delta` from where the
 *   arm reports it now, in `ms` (default 300); what a teleop panel or a gamepad sends per step.
 *
 * Both become frames through ./ros2's `trajectoryFrames` (the ROS 2 bridge's: one home for
 * joint values → frames); the controller core then checks them as any command. Pure.
 */
import { jointFromServo, servoFromPwm } from '@armtwin/robot';
import { trajectoryFrames, type JointTrajectoryMsg, type TrajectoryFrames } from '@armtwin/ros2';
import type { RobotFolder } from '@armtwin/motion/robot-folder';

export const COMMAND_TOPICS = ['joint_trajectory', 'jog'] as const;
export type CommandTopic = (typeof COMMAND_TOPICS)[number];

/** A trajectory is streamed as one frame group this often, ms (as the ROS 2 bridge does). */
export const STEP_MS = 100;
export const DEFAULT_JOG_MS = 300;

/** `/{arm}/{command}` → its parts, or null for a topic that is not a command. */
export function commandTopic(t: string): { armId: string; command: CommandTopic } | null {
  const m = /^\/([a-z0-9-]{1,32})\/([a-z_]+)$/.exec(t);
  if (!m || !(COMMAND_TOPICS as readonly string[]).includes(m[2]!)) return null;
  return { armId: m[1]!, command: m[2] as CommandTopic };
}

const refused = (message: string): TrajectoryFrames => ({
  kind: 'refused',
  reason: 'bad-point',
  message,
});

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null;

function trajectoryOf(v: unknown): JointTrajectoryMsg | string {
  if (!isObject(v) || !Array.isArray(v.joint_names) || !Array.isArray(v.points))
    return 'a JointTrajectory needs joint_names and points';
  const points = [];
  for (const p of v.points as unknown[]) {
    if (!isObject(p) || !Array.isArray(p.positions)) return 'each point needs positions';
    const t = p.time_from_start;
    const ms =
      typeof p.time_from_start_ms === 'number'
        ? p.time_from_start_ms
        : isObject(t) && typeof t.sec === 'number'
          ? t.sec * 1000 + (typeof t.nsec === 'number' ? t.nsec / 1e6 : 0)
          : NaN;
    points.push({ positions: p.positions as number[], time_from_start_ms: ms });
  }
  return { joint_names: (v.joint_names as unknown[]).map(String), points };
}

/** The frames of one client message on `command` for the arm of `folder`, from pose `pwm`. */
export function commandFrames(
  folder: RobotFolder,
  pwm: readonly number[],
  command: CommandTopic,
  data: Uint8Array,
): TrajectoryFrames {
  let v: unknown;
  try {
    v = JSON.parse(new TextDecoder().decode(data));
  } catch {
    return refused(`${command}: not JSON (this server takes the json encoding)`);
  }
  let traj: JointTrajectoryMsg | string;
  switch (command) {
    case 'joint_trajectory':
      traj = trajectoryOf(v);
      break;
    case 'jog': {
      if (!isObject(v) || typeof v.joint !== 'string' || typeof v.delta !== 'number')
        return refused('jog needs {"joint": NAME, "delta": rad, "ms": 300}');
      const i = folder.profile.servos.findIndex((s) => s.joint === v.joint);
      const servo = folder.profile.servos[i];
      const ms = typeof v.ms === 'number' ? v.ms : DEFAULT_JOG_MS;
      const now = servo ? jointFromServo(servo, servoFromPwm(servo, pwm[i]!)) : NaN;
      traj = {
        joint_names: [v.joint],
        points: [{ positions: [now + v.delta], time_from_start_ms: ms }],
      };
      if (servo && !Number.isFinite(now))
        return { kind: 'refused', reason: 'no-state', message: 'the arm has not reported yet' };
      break;
    }
    default: {
      const never: never = command;
      return never;
    }
  }
  if (typeof traj === 'string') return refused(traj);
  return trajectoryFrames(folder.profile, folder.robot.table, pwm, traj, STEP_MS);
}
