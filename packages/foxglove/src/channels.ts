/**
 * The Foxglove channels one arm is shown on (`/{arm}/…`), all JSON-encoded with JSON schemas:
 * Foxglove's own schemas where one fits (its 3D panel, plots and log read them without setup),
 * armtwin's where none does. The channel kinds are declared once here; the server advertises
 * each arm's set when the arm announces its profile. Pure.
 */
import { FrameTransforms, JointStates, Log } from '@foxglove/schemas/jsonschema';

export const CHANNEL_KINDS = [
  'joint_states',
  'targets',
  'tf',
  'robot_description',
  'health',
  'log',
] as const;
export type ChannelKind = (typeof CHANNEL_KINDS)[number];

/** Channels sent to each new subscriber at once with the last message (as ROS latches them). */
export const LATCHED: ReadonlySet<ChannelKind> = new Set(['robot_description']);

const time = {
  type: 'object',
  properties: { sec: { type: 'integer', minimum: 0 }, nsec: { type: 'integer', minimum: 0 } },
} as const;

const TARGETS = {
  title: 'armtwin.JointTargets',
  description:
    'Where the arm was last sent (PROTOCOL.md §1, §8): every joint in servo order, URDF units (rad, m); a joint the command moves has its ms, the others hold (ms 0); by whom',
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

const STRING = {
  title: 'std_msgs/String',
  description:
    'The robot description: the URDF, meshes as package://<profile>/… (fetched as assets)',
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

const SCHEMAS: Record<ChannelKind, { title: string }> = {
  joint_states: JointStates,
  targets: TARGETS,
  tf: FrameTransforms,
  robot_description: STRING,
  health: HEALTH,
  log: Log,
};

/** A channel as the protocol's `advertise` carries it (less the id the server gives it). */
export interface ChannelSpec {
  topic: string;
  encoding: 'json';
  schemaName: string;
  schema: string;
  schemaEncoding: 'jsonschema';
}

export const channelTopic = (armId: string, kind: ChannelKind): string => `/${armId}/${kind}`;

/** Every channel of arm `armId`, in CHANNEL_KINDS order. */
export function armChannels(armId: string): { kind: ChannelKind; spec: ChannelSpec }[] {
  return CHANNEL_KINDS.map((kind) => ({
    kind,
    spec: {
      topic: channelTopic(armId, kind),
      encoding: 'json',
      schemaName: SCHEMAS[kind].title,
      schema: JSON.stringify(SCHEMAS[kind]),
      schemaEncoding: 'jsonschema',
    },
  }));
}

/** Epoch ms → the protocol's nanoseconds and a schema's `{sec, nsec}`. */
export function stampOf(ms: number): { ns: bigint; time: { sec: number; nsec: number } } {
  const whole = Math.floor(ms);
  const sec = Math.floor(whole / 1000);
  const nsec = Math.round((ms - sec * 1000) * 1e6);
  return { ns: BigInt(sec) * 1_000_000_000n + BigInt(nsec), time: { sec, nsec } };
}
