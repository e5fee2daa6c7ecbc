/**
 * The one home of the topic names and schemas an arm's data has in Foxglove and Lichtblick: the
 * live server (./channels.ts, docs/foxglove.md) advertises them, the MCAP export
 * (apps/middleware/src/export, docs/foxglove-mcap.md) writes them, and the layout
 * deploy/foxglove/armtwin-arm.json reads them, so one layout serves a recording and a live arm.
 * JSON schemas: Foxglove's own where one fits (its 3D panel, plots and log read them without
 * setup), armtwin's where none does. Pure (no I/O, no server): the export imports it alone.
 */
import { FrameTransforms, JointStates, Log } from '@foxglove/schemas/jsonschema';

export const CHANNEL_KINDS = [
  'joint_states',
  'targets',
  'tf',
  'robot_description',
  'health',
  'log',
  'plan',
  'plan_tf',
] as const;
export type ChannelKind = (typeof CHANNEL_KINDS)[number];

export const channelTopic = (armId: string, kind: ChannelKind): string => `/${armId}/${kind}`;

/** An arm's camera `camId` (foxglove.CompressedImage, live only: PROTOCOL.md §7 cameras). */
export const cameraChannelTopic = (armId: string, camId: string): string =>
  `/${armId}/camera/${camId}`;

/** The per-arm topics by what they carry (the names the export's code reads best). */
export const FOXGLOVE_TOPICS = {
  /** The URDF (std_msgs/String shape: `{"data": "<robot …>"}`). */
  robotDescription: (arm: string) => channelTopic(arm, 'robot_description'),
  /** foxglove.FrameTransforms: every URDF joint's parent → child transform. */
  transforms: (arm: string) => channelTopic(arm, 'tf'),
  /** foxglove.JointStates: the profile's joints as reported, servo order. */
  jointStates: (arm: string) => channelTopic(arm, 'joint_states'),
  /** armtwin.JointTargets: the joints as last commanded, every joint, servo order. */
  targets: (arm: string) => channelTopic(arm, 'targets'),
  /** armtwin.ServoHealth, per report (live only: the export keeps health in its servo samples). */
  health: (arm: string) => channelTopic(arm, 'health'),
  /** foxglove.Log: the control log (who took, gave, lost control; refusals; alarms). */
  log: (arm: string) => channelTopic(arm, 'log'),
  /** armtwin.PlannedPose: where each motion request's plan ends (live only). */
  plan: (arm: string) => channelTopic(arm, 'plan'),
  /** foxglove.FrameTransforms of that pose, frames prefixed `plan/` (the 3D panel's ghost). */
  planTransforms: (arm: string) => channelTopic(arm, 'plan_tf'),
  /** foxglove.CompressedImage (jpeg), per camera (live only). */
  camera: cameraChannelTopic,
} as const;

const time = {
  type: 'object',
  properties: { sec: { type: 'integer', minimum: 0 }, nsec: { type: 'integer', minimum: 0 } },
} as const;

const TARGETS = {
  title: 'armtwin.JointTargets',
  description:
    'Where the arm was last sent (PROTOCOL.md §1, §8): every joint in servo order, URDF units (rad, m); live, a joint the command moves has its ms, the others hold (ms 0), and by whom',
  type: 'object',
  properties: {
    timestamp: time,
    by: { type: 'string', description: "the command's author ('' = the plain control topic)" },
    joints: {
      type: 'array',
      items: {
        type: 'object',
        properties: {
          name: { type: 'string' },
          position: { type: 'number' },
          ms: { type: 'integer' },
        },
      },
    },
  },
} as const;

/**
 * A robot description: ROS's std_msgs/String (`data`), the schema name the 3D panel's URDF layer
 * accepts for a topic source.
 */
const ROBOT_DESCRIPTION = {
  title: 'std_msgs/String',
  description:
    "A robot's URDF: live, meshes as package://<profile>/… (fetched as assets); in an MCAP export, inline as data: URIs",
  type: 'object',
  properties: { data: { type: 'string' } },
} as const;

const HEALTH = {
  title: 'armtwin.ServoHealth',
  description: "One servo's health report (PROTOCOL.md §1): temperature, supply, and their level",
  type: 'object',
  properties: {
    timestamp: time,
    id: { type: 'string' },
    joint: { type: 'string' },
    temp: { type: 'number', description: '°C' },
    volt: { type: 'number', description: 'supply, V' },
    level: { type: 'string', enum: ['normal', 'warning', 'critical'] },
  },
} as const;

const PLANNED_POSE = {
  title: 'armtwin.PlannedPose',
  description:
    "Where a motion request's plan ends (docs/protocol.md § Motion requests: the feedback's `end`), as joints in servo order, URDF units (rad, m): the HUD's ghost of a plan",
  type: 'object',
  properties: {
    timestamp: time,
    id: { type: 'string', description: "the request's id" },
    status: { type: 'string', description: '`planned`, or `replanned` during execution' },
    mode: { type: 'string', enum: ['joint', 'cartesian'] },
    durationMs: { type: 'number' },
    joints: {
      type: 'array',
      items: {
        type: 'object',
        properties: { name: { type: 'string' }, position: { type: 'number' } },
      },
    },
  },
} as const;

/** A plan's frames are the arm's own with this prefix (a second URDF layer's frame prefix). */
export const PLAN_FRAME_PREFIX = 'plan/';

/** Each kind's JSON schema (its `title` is the schema name advertised or written). */
export const CHANNEL_SCHEMAS: Record<ChannelKind, { title: string }> = {
  joint_states: JointStates,
  targets: TARGETS,
  tf: FrameTransforms,
  robot_description: ROBOT_DESCRIPTION,
  health: HEALTH,
  log: Log,
  plan: PLANNED_POSE,
  plan_tf: FrameTransforms,
};
