/**
 * The JSON lines between @armtwin/ros2 and its rclpy process (python/armtwin_ros2/bridge.py):
 * commands in on stdin, events out on stdout, one JSON object a line. Only these plain shapes
 * cross: no ROS message type reaches TypeScript. Times are milliseconds; joint positions are
 * ROS's (radians, metres).
 */
import { z } from 'zod';

/** The message kinds the bridge carries: sensor_msgs/JointState, trajectory_msgs/JointTrajectory, std_msgs/String. */
export const ROS2_MESSAGE_TYPES = ['joint_state', 'joint_trajectory', 'string'] as const;
export type Ros2MessageType = (typeof ROS2_MESSAGE_TYPES)[number];

export interface JointStateMsg {
  /** header.stamp, epoch ms (absent when publishing: the bridge stamps it now). */
  stamp_ms?: number;
  name: string[];
  position: number[];
  velocity?: number[];
  effort?: number[];
}

export interface TrajectoryPointMsg {
  positions: number[];
  velocities?: number[];
  time_from_start_ms: number;
}

export interface JointTrajectoryMsg {
  joint_names: string[];
  points: TrajectoryPointMsg[];
}

export interface StringMsg {
  data: string;
}

export interface Ros2Messages {
  joint_state: JointStateMsg;
  joint_trajectory: JointTrajectoryMsg;
  string: StringMsg;
}

export type Ros2Command =
  | { op: 'subscribe'; id?: number; topic: string; type: Ros2MessageType; durable?: boolean }
  | {
      op: 'publish';
      id?: number;
      topic: string;
      type: Ros2MessageType;
      msg: Ros2Messages[Ros2MessageType];
      durable?: boolean;
      wait_ms?: number;
    }
  | {
      op: 'advertise';
      id?: number;
      topic: string;
      type: Ros2MessageType;
      durable?: boolean;
      wait_ms?: number;
    };

/** What the bridge reports as wrong with a command (`ros`: rclpy refused it, e.g. a bad topic name). */
export const ROS2_ERROR_KINDS = ['bad-json', 'bad-command', 'bad-message', 'ros'] as const;

const numbers = z.array(z.number());
const jointState = z.object({
  stamp_ms: z.number().optional(),
  name: z.array(z.string()),
  position: numbers,
  velocity: numbers.optional(),
  effort: numbers.optional(),
});
const jointTrajectory = z.object({
  joint_names: z.array(z.string()),
  points: z.array(
    z.object({
      positions: numbers,
      velocities: numbers.optional(),
      time_from_start_ms: z.number(),
    }),
  ),
});
const stringMsg = z.object({ data: z.string() });

const message = z.discriminatedUnion('type', [
  z.object({ type: z.literal('joint_state'), msg: jointState }),
  z.object({ type: z.literal('joint_trajectory'), msg: jointTrajectory }),
  z.object({ type: z.literal('string'), msg: stringMsg }),
]);

const event = z.union([
  z.object({ ev: z.literal('ready'), domain: z.number(), node: z.string() }),
  z.object({ ev: z.literal('ack'), id: z.number(), subscribers: z.number().optional() }),
  z.intersection(z.object({ ev: z.literal('message'), topic: z.string() }), message),
  z.object({
    ev: z.literal('error'),
    kind: z.enum(ROS2_ERROR_KINDS),
    message: z.string(),
    id: z.number().nullish(),
  }),
]);

export type Ros2Event = z.infer<typeof event>;
export type Ros2MessageEvent = Extract<Ros2Event, { ev: 'message' }>;

/** One stdout line as an event, or why it is not one. */
export function parseEvent(
  line: string,
): { ok: true; event: Ros2Event } | { ok: false; error: string } {
  let json: unknown;
  try {
    json = JSON.parse(line);
  } catch {
    return { ok: false, error: `not JSON: ${line.slice(0, 120)}` };
  }
  const r = event.safeParse(json);
  return r.success
    ? { ok: true, event: r.data }
    : { ok: false, error: `not a bridge event: ${line.slice(0, 120)}` };
}
