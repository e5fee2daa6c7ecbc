/**
 * A recording as an MCAP file (the format Foxglove and Lichtblick open), written with the
 * maintained `@mcap/core` writer, messages JSON-encoded with JSON schemas:
 *   /arm/{arm}/servo/{id}     armtwin.ServoSample  one per stored `servo` point: pwm, angle, temp, volt
 *   /arm/{arm}/command/{id}   armtwin.Command      one per stored `command` point
 *   /arm/{arm}/ik             armtwin.IkResult     one per stored `ik` point
 *   /arm/{arm}/joint_states   foxglove.JointStates the profile's joints at each reported instant
 *   /tf                       foxglove.FrameTransforms every URDF joint's transform at those instants
 *   /arm/{arm}/audit          foxglove.Log         one per control event (who took, gave, lost control)
 * The last two need the arm's robot (profile and URDF); without it they are left out. Every
 * message's log and publish time is the point's own time. Messages go out in time order.
 */
import type { Writable } from 'node:stream';
import { McapWriter, type IWritable } from '@mcap/core';
import { FrameTransforms, JointStates, Log } from '@foxglove/schemas/jsonschema';
import type { Profile, UrdfJoint } from '@armtwin/robot';
import type { Recording } from './recording.ts';
import { jointSamples, linkTransforms, type JointSample } from './robot-motion.ts';

/** The robot a recording's arm is: its profile and its URDF's joints. */
export interface RecordingRobot {
  profile: Profile;
  joints: readonly UrdfJoint[];
}

const number = { type: 'number' } as const;
const timestamp = {
  type: 'object',
  properties: { sec: { type: 'integer', minimum: 0 }, nsec: { type: 'integer', minimum: 0 } },
} as const;

const SCHEMAS = {
  servo: {
    title: 'armtwin.ServoSample',
    description: 'One stored servo point (PROTOCOL.md §6): a position or health report',
    type: 'object',
    properties: {
      timestamp,
      id: { type: 'string' },
      pwm: { type: 'integer', description: 'pulse width, µs' },
      angle: { ...number, description: 'servo angle, degrees' },
      temp: { ...number, description: '°C' },
      volt: { ...number, description: 'supply, V' },
    },
  },
  command: {
    title: 'armtwin.Command',
    description: 'One stored command point (PROTOCOL.md §6): what a servo was asked',
    type: 'object',
    properties: {
      timestamp,
      id: { type: 'string' },
      pwm: { type: 'integer' },
      angle: number,
      ms: { type: 'integer' },
    },
  },
  ik: {
    title: 'armtwin.IkResult',
    description: 'One stored $KMS outcome (PROTOCOL.md §4, §6)',
    type: 'object',
    properties: {
      timestamp,
      code: { type: 'integer' },
      x: number,
      y: number,
      z: number,
      a: number,
    },
  },
} as const;

/** foxglove.LogLevel: INFO, WARNING. Refusals and lost or taken-over control are warnings. */
const LOG_INFO = 2;
const LOG_WARNING = 3;
const WARNING_KINDS = new Set([
  'refused',
  'refused-command',
  'refused-claim',
  'lost',
  'admin-take-over',
]);

/** How many messages went to each topic. */
export type McapCounts = Record<string, number>;

const stamp = (ns: bigint) => ({
  sec: Number(ns / 1_000_000_000n),
  nsec: Number(ns % 1_000_000_000n),
});
const encoder = new TextEncoder();
const json = (v: unknown) => encoder.encode(JSON.stringify(v));

/** An `IWritable` over a Node stream: waits for each chunk to be taken. */
export function streamWritable(stream: Writable): IWritable {
  let written = 0n;
  return {
    write: (buffer) =>
      new Promise<void>((resolve, reject) => {
        stream.write(buffer, (err) => (err ? reject(err) : resolve()));
        written += BigInt(buffer.byteLength);
      }),
    position: () => written,
  };
}

interface Timed {
  ns: bigint;
  write: () => Promise<void>;
}

export async function writeMcap(
  rec: Recording,
  robot: RecordingRobot | null,
  writable: IWritable,
  library = 'armtwin export',
): Promise<McapCounts> {
  const w = new McapWriter({ writable, useStatistics: true, useChunks: true, useChunkIndex: true });
  await w.start({ profile: '', library });
  await w.addMetadata({
    name: 'armtwin',
    metadata: new Map([
      ['arm', rec.arm],
      ['start', new Date(rec.startMs).toISOString()],
      ['stop', new Date(rec.stopMs).toISOString()],
      ['robot', robot?.profile.name ?? ''],
    ]),
  });
  const schemaIds = new Map<string, number>();
  const schema = async (s: { title: string }) => {
    let id = schemaIds.get(s.title);
    if (id === undefined) {
      id = await w.registerSchema({ name: s.title, encoding: 'jsonschema', data: json(s) });
      schemaIds.set(s.title, id);
    }
    return id;
  };
  const counts: McapCounts = {};
  const channels = new Map<string, { id: number; seq: number }>();
  const channel = async (topic: string, s: { title: string }) => {
    let c = channels.get(topic);
    if (!c) {
      const schemaId = await schema(s);
      c = {
        id: await w.registerChannel({
          topic,
          schemaId,
          messageEncoding: 'json',
          metadata: new Map(),
        }),
        seq: 0,
      };
      channels.set(topic, c);
    }
    return c;
  };
  const add = async (topic: string, s: { title: string }, ns: bigint, body: object) => {
    const c = await channel(topic, s);
    await w.addMessage({
      channelId: c.id,
      sequence: c.seq++,
      logTime: ns,
      publishTime: ns,
      data: json({ timestamp: stamp(ns), ...body }),
    });
    counts[topic] = (counts[topic] ?? 0) + 1;
  };

  const base = `/arm/${rec.arm}`;
  const streams: Timed[][] = [
    rec.servo.map(({ ns, ...r }) => ({
      ns,
      write: () => add(`${base}/servo/${r.id}`, SCHEMAS.servo, ns, r),
    })),
    rec.command.map(({ ns, ...r }) => ({
      ns,
      write: () => add(`${base}/command/${r.id}`, SCHEMAS.command, ns, r),
    })),
    rec.ik.map(({ ns, ...r }) => ({ ns, write: () => add(`${base}/ik`, SCHEMAS.ik, ns, r) })),
    rec.audit.map(({ ns, ...e }) => ({
      ns,
      write: () =>
        add(`${base}/audit`, Log, ns, {
          level: WARNING_KINDS.has(e.kind) ? LOG_WARNING : LOG_INFO,
          message: e.detail,
          name: `${e.kind} by ${e.by || 'the plain control topic'}`,
          file: '',
          line: 0,
        }),
    })),
  ];
  if (robot)
    streams.push(jointSamples(robot.profile, rec.servo).map((s) => motion(s, robot, base, add)));
  await mergeInTimeOrder(streams);
  await w.end();
  return counts;
}

/** The joint states and link transforms of one sample. */
function motion(
  s: JointSample,
  robot: RecordingRobot,
  base: string,
  add: (topic: string, schema: { title: string }, ns: bigint, body: object) => Promise<void>,
): Timed {
  return {
    ns: s.ns,
    write: async () => {
      const known = s.names.flatMap((name, i) =>
        Number.isFinite(s.positions[i]) ? [{ name, position: s.positions[i]! }] : [],
      );
      await add(`${base}/joint_states`, JointStates, s.ns, { joints: known });
      const values = new Map(known.map((j) => [j.name, j.position]));
      const transforms = linkTransforms(robot.joints, values).map((t) => ({
        timestamp: stamp(s.ns),
        parent_frame_id: t.parent,
        child_frame_id: t.child,
        translation: { x: t.translation[0], y: t.translation[1], z: t.translation[2] },
        rotation: { x: t.rotation[0], y: t.rotation[1], z: t.rotation[2], w: t.rotation[3] },
      }));
      await add('/tf', FrameTransforms, s.ns, { transforms });
    },
  };
}

/** Writes several time-ordered streams as one, oldest first (ties: the earlier stream first). */
async function mergeInTimeOrder(streams: Timed[][]): Promise<void> {
  const at = streams.map(() => 0);
  for (;;) {
    let best = -1;
    for (let i = 0; i < streams.length; i++) {
      const next = streams[i]![at[i]!];
      if (next && (best < 0 || next.ns < streams[best]![at[best]!]!.ns)) best = i;
    }
    if (best < 0) return;
    await streams[best]![at[best]!++]!.write();
  }
}
