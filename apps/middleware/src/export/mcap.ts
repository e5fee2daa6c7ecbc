/**
 * A recording as an MCAP file (the format Foxglove and Lichtblick open), written with the
 * maintained `@mcap/core` writer, messages JSON-encoded with JSON schemas (names: topics.ts; the
 * `/{arm}/…` topics' names and schemas are the live Foxglove server's, @armtwin/foxglove/topics):
 *   /arm/{arm}/servo/{id}     armtwin.ServoSample  one per stored `servo` point: pwm, angle, temp, volt
 *   /arm/{arm}/command/{id}   armtwin.Command      one per stored `command` point
 *   /arm/{arm}/ik             armtwin.IkResult     one per stored `ik` point
 *   /{arm}/log                foxglove.Log         one per control event (who took, gave, lost control);
 *                                                  the channel is there when no event is
 *   /{arm}/robot_description  std_msgs/String      the URDF, meshes inline, once at the range's start
 *   /{arm}/joint_states       foxglove.JointStates the profile's joints at each reported instant
 *   /{arm}/targets            armtwin.JointTargets the joints as commanded, at each command (all joints)
 *   /{arm}/tf                 foxglove.FrameTransforms every URDF joint's transform at each report
 * The last four need the arm's robot (profile and URDF); without it they are left out. Every
 * message's log and publish time is the point's own time. Messages go out in time order.
 */
import type { Writable } from 'node:stream';
import { McapWriter, type IWritable } from '@mcap/core';
import { CHANNEL_SCHEMAS } from '@armtwin/foxglove/topics';
import type { Profile, UrdfJoint } from '@armtwin/robot';
import type { ProfileSource } from './arm-profile.ts';
import type { Recording } from './recording.ts';
import type { RobotDescription } from './robot-description.ts';
import { jointSamples, linkTransforms, targetSamples, type JointSample } from './robot-motion.ts';
import { SCHEMAS } from './schemas.ts';
import { FOXGLOVE_TOPICS as TOPICS } from './topics.ts';

/** The live server's schemas for the topics both write (one home: @armtwin/foxglove/topics). */
const LIVE = CHANNEL_SCHEMAS;

/** The robot a recording's arm is: its profile, its URDF's joints and description. */
export interface RecordingRobot {
  profile: Profile;
  joints: readonly UrdfJoint[];
  /** The URDF with its meshes inline, for the 3D panel (absent: no robot description topic). */
  description?: RobotDescription;
  /** How the profile was found (kept in the file's metadata). */
  source?: ProfileSource;
}

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
      ['profileSource', robot?.source ?? ''],
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

  const arm = rec.arm;
  // The control log's channel even with no event in range: a Log panel finds its topic.
  await channel(TOPICS.log(arm), LIVE.log);
  const streams: Timed[][] = [
    rec.servo.map(({ ns, ...r }) => ({
      ns,
      write: () => add(TOPICS.servo(arm, r.id), SCHEMAS.servo, ns, r),
    })),
    rec.command.map(({ ns, ...r }) => ({
      ns,
      write: () => add(TOPICS.command(arm, r.id), SCHEMAS.command, ns, r),
    })),
    rec.ik.map(({ ns, ...r }) => ({ ns, write: () => add(TOPICS.ik(arm), SCHEMAS.ik, ns, r) })),
    rec.audit.map(({ ns, ...e }) => ({
      ns,
      write: () =>
        add(TOPICS.log(arm), LIVE.log, ns, {
          level: WARNING_KINDS.has(e.kind) ? LOG_WARNING : LOG_INFO,
          message: e.detail,
          name: `${e.kind} by ${e.by || 'the plain control topic'}`,
          file: '',
          line: 0,
        }),
    })),
  ];
  if (robot) {
    const description = robot.description;
    if (description) {
      const ns = BigInt(rec.startMs) * 1_000_000n;
      const data = { data: description.urdf };
      streams.push([
        { ns, write: () => add(TOPICS.robotDescription(arm), LIVE.robot_description, ns, data) },
      ]);
    }
    const reported = jointSamples(robot.profile, rec.servo);
    streams.push(reported.map((s) => motion(s, robot, arm, add)));
    streams.push(
      targetSamples(jointSamples(robot.profile, rec.command), reported).map((s) => ({
        ns: s.ns,
        write: () => add(TOPICS.targets(arm), LIVE.targets, s.ns, { joints: known(s) }),
      })),
    );
  }
  await mergeInTimeOrder(streams);
  await w.end();
  return counts;
}

/** A sample's joints that have a value (a servo with no report yet is left out). */
const known = (s: JointSample) =>
  s.names.flatMap((name, i) =>
    Number.isFinite(s.positions[i]) ? [{ name, position: s.positions[i]! }] : [],
  );

/** The joint states and link transforms of one sample. */
function motion(
  s: JointSample,
  robot: RecordingRobot,
  arm: string,
  add: (topic: string, schema: { title: string }, ns: bigint, body: object) => Promise<void>,
): Timed {
  return {
    ns: s.ns,
    write: async () => {
      const joints = known(s);
      await add(TOPICS.jointStates(arm), LIVE.joint_states, s.ns, { joints });
      const values = new Map(joints.map((j) => [j.name, j.position]));
      const transforms = linkTransforms(robot.joints, values).map((t) => ({
        timestamp: stamp(s.ns),
        parent_frame_id: t.parent,
        child_frame_id: t.child,
        translation: { x: t.translation[0], y: t.translation[1], z: t.translation[2] },
        rotation: { x: t.rotation[0], y: t.rotation[1], z: t.rotation[2], w: t.rotation[3] },
      }));
      await add(TOPICS.transforms(arm), LIVE.tf, s.ns, { transforms });
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
