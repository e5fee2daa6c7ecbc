/**
 * An arm's history in Foxglove, as a user gets it: a simulated SO-101 (`armtwin sim --profile
 * so101`) moves on the real Mosquitto, the middleware stores its reports and its announced
 * profile in the real influxd, and `armtwin export --arm ID --from … --to … --out F` is typed
 * with no `--profile`. The file is read with Foxglove's own TypeScript reader (`@mcap/core`'s
 * McapIndexedReader, what Foxglove and Lichtblick open MCAP with), not ours:
 *   - the robot description is on /{arm}/robot_description, parses, has the URDF's links and joints,
 *     and every mesh is inline, byte for byte the robot folder's file;
 *   - the per-link transforms on /{arm}/tf put every link where the IK's own chain FK does (within
 *     0.1 mm) at sample times, for the joint values of the samples InfluxDB holds;
 *   - the joint states are the stored samples, in the profile's joint units;
 *   - every topic the Foxglove layout deploy/foxglove/armtwin-arm.json reads is in the file;
 *   - every `/{arm}/…` topic has the live Foxglove server's name and schema (one home for both).
 */
import fs from 'node:fs';
import path from 'node:path';
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { McapIndexedReader, type IReadable } from '@mcap/core';
import { connectAsync } from 'mqtt';
import { chainFkFrames, createFkFrames } from '@armtwin/ik';
import {
  chainFromUrdf,
  jointFromServo,
  meshRefs,
  parseProfile,
  parseUrdfJoints,
  profileAnnouncement,
  type Profile,
} from '@armtwin/robot';
import { MODELS_DIR } from '@armtwin/motion/robot-folder';
import { armChannels } from '@armtwin/foxglove';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { select, waitForValue } from '../../apps/middleware/test/support/harness.ts';
import { REPO_ROOT } from '../helpers/files.ts';
import { layoutPanels, layoutTopics, liveOnly, readLayout } from '../helpers/foxglove-layout.ts';
import { ARMTWIN, armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const run = promisify(execFile);
const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('export-foxglove', () => ({ mqttUrl: broker().url, influx: influx() }));
const ARM = 'arm1'; // the arm the layout is made for
const FOLDER = path.join(MODELS_DIR, 'so101');
const profile = (() => {
  const r = parseProfile(JSON.parse(fs.readFileSync(path.join(FOLDER, 'profile.json'), 'utf8')));
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
})();
const URDF = fs.readFileSync(path.join(FOLDER, profile.urdf), 'utf8');
let sim: Child | undefined;
let watcher: StatusWatcher | undefined;

interface Message {
  topic: string;
  schema: string;
  ns: bigint;
  data: Record<string, unknown>;
}
interface Exported {
  stderr: string;
  messages: Message[];
  /** Every channel's topic and schema name, messages or not. */
  channels: Map<string, string>;
  metadata: Map<string, string>;
}
let exported: Exported;

/** A file as `@mcap/core` reads it. */
function fileReadable(fd: fs.promises.FileHandle, size: number): IReadable {
  return {
    size: () => Promise.resolve(BigInt(size)),
    read: async (offset, length) => {
      const buf = Buffer.alloc(Number(length));
      await fd.read(buf, 0, buf.length, Number(offset));
      return buf;
    },
  };
}

async function readMcap(file: string): Promise<Omit<Exported, 'stderr'>> {
  const fd = await fs.promises.open(file, 'r');
  try {
    const reader = await McapIndexedReader.Initialize({
      readable: fileReadable(fd, (await fd.stat()).size),
    });
    const decoder = new TextDecoder();
    const messages: Message[] = [];
    for await (const m of reader.readMessages()) {
      const channel = reader.channelsById.get(m.channelId)!;
      messages.push({
        topic: channel.topic,
        schema: reader.schemasById.get(channel.schemaId)?.name ?? '',
        ns: m.logTime,
        data: JSON.parse(decoder.decode(m.data)) as Record<string, unknown>,
      });
    }
    const channels = new Map(
      [...reader.channelsById.values()].map((c) => [
        c.topic,
        reader.schemasById.get(c.schemaId)?.name ?? '',
      ]),
    );
    const metadata = new Map<string, string>();
    for await (const md of reader.readMetadata({ name: 'armtwin' }))
      for (const [k, v] of md.metadata) metadata.set(k, v);
    return { messages, channels, metadata };
  } finally {
    await fd.close();
  }
}

const inf = () => ({ url: influx().url, db: influx().db });

/** The stored angle samples of the arm: time (µs) → servo id (a number) → angle. */
async function storedAngles(): Promise<Map<number, Map<number, number>>> {
  const rows = await select(
    inf(),
    `SELECT "angle", "id" FROM "servo" WHERE "arm" = '${ARM}' AND "angle" > -1000`,
  );
  const out = new Map<number, Map<number, number>>();
  for (const [t, angle, id] of rows as [number, number, string][]) {
    const at = out.get(t) ?? new Map<number, number>();
    at.set(Number(id), angle);
    out.set(t, at);
  }
  return out;
}

/** Where a servo's latest state-group frame says it is, degrees. */
function reportedDeg(w: StatusWatcher, id: number): number | undefined {
  for (let i = w.items.length - 1; i >= 0; i--) {
    const it = w.items[i]!;
    if (!('group' in it)) continue;
    const f = it.group.frames.find((x) => 'id' in x && x.id === id);
    if (f?.type === 'angle') return f.deg;
  }
  return undefined;
}

async function moveTo(w: StatusWatcher, deg: Record<number, number>, ms: number) {
  const frames = Object.entries(deg).map(
    ([id, d]) =>
      `#${id.padStart(3, '0')}A${d < 0 ? '-' : '+'}${Math.abs(d).toFixed(2).padStart(6, '0')}T${String(ms).padStart(4, '0')}!`,
  );
  await w.send(`{${frames.join('')}}`);
  await w.until(
    () =>
      Object.entries(deg).every(
        ([id, d]) => Math.abs((reportedDeg(w, Number(id)) ?? 1e9) - d) < 0.01,
      )
        ? true
        : undefined,
    15_000,
    `servos at ${JSON.stringify(deg)}`,
  );
}

beforeAll(async () => {
  await mws.spawn({ env: { FLUSH_INTERVAL_MS: '200' } });
  const from = new Date(Date.now() - 1000);
  watcher = await StatusWatcher.connect(broker().url, ARM);
  sim = armtwin([
    'sim',
    '--mqtt',
    broker().url,
    '--arm',
    ARM,
    '--profile',
    'so101',
    '--rate',
    '20',
  ]);
  await watcher.until(
    () => (watcher!.retained.get(`arm/${ARM}/online`) === '1' ? true : undefined),
    20_000,
    'online 1',
  );
  await moveTo(watcher, { 1: 30, 2: -20, 3: 45, 4: 10, 5: -60 }, 600);
  await moveTo(watcher, { 1: -15, 3: 20, 6: 25 }, 400);
  const to = new Date(Date.now() + 500);
  await new Promise((r) => setTimeout(r, 800)); // the last reports of the range
  // Everything in the range is stored: the profile point, and samples up to its end.
  const last = (to.getTime() - 300) * 1000;
  await waitForValue(
    async () => {
      const p = await select(inf(), `SELECT "name" FROM "profile" WHERE "arm" = '${ARM}'`);
      const s = await select(inf(), `SELECT last("angle") FROM "servo" WHERE "arm" = '${ARM}'`);
      return p.length > 0 && Number(s[0]?.[0] ?? 0) >= last;
    },
    true,
    20_000,
  );
  exported = await exportAs(ARM, from, to);
}, 120_000);

/** `armtwin export --arm ARM --from --to --out F`, as a user types it, read back. */
async function exportAs(arm: string, from: Date, to: Date): Promise<Exported> {
  const file = path.join(mws.dir(), `${arm}.mcap`);
  const args = ['export', '--arm', arm, '--from', from.toISOString(), '--to', to.toISOString()];
  const { stderr } = await run(process.execPath, [ARMTWIN, ...args, '--out', file], {
    cwd: REPO_ROOT,
    timeout: 60_000,
    env: {
      ...process.env,
      INFLUX_URL: influx().url,
      INFLUX_BUCKET: influx().bucket,
      INFLUX_TOKEN: '',
      INFLUX_ORG: '',
      MQTT_URL: broker().url,
    },
  });
  return { stderr, ...(await readMcap(file)) };
}

afterAll(async () => {
  await sim?.stop('SIGKILL');
  await watcher?.close();
});

const on = (topic: string) => exported.messages.filter((m) => m.topic === topic);

describe('armtwin export --arm ID --format mcap, typed without --profile, in Foxglove', () => {
  test('finds the profile the arm announced, stored with its history, and says so', () => {
    expect(exported.stderr).toContain(
      'profile so101 (as the arm announced it, stored with its history)',
    );
    expect(exported.metadata.get('robot')).toBe('so101');
    expect(exported.metadata.get('profileSource')).toBe('history');
  });

  test("the robot description parses, has the URDF's links, and carries every mesh", () => {
    const [desc, ...more] = on(`/${ARM}/robot_description`);
    expect(more).toEqual([]);
    expect(desc!.schema).toBe('std_msgs/String');
    const urdf = desc!.data.data as string;
    const parsed = parseUrdfJoints(urdf);
    const shipped = parseUrdfJoints(URDF);
    if (!parsed.ok || !shipped.ok) throw new Error('URDF does not parse');
    const links = (joints: typeof parsed.joints) =>
      new Set(joints.flatMap((j) => [j.parent, j.child]));
    expect(links(parsed.joints)).toEqual(links(shipped.joints));
    expect(links(parsed.joints)).toContain('gripper_frame_link');
    const names = meshRefs(URDF).map((m) => m.filename);
    const inline = meshRefs(urdf).map((m) => m.filename);
    expect(inline).toHaveLength(names.length);
    inline.forEach((uri, i) => {
      const m = /^data:model\/stl;base64,(.+)$/.exec(uri);
      expect(m, names[i]).not.toBeNull();
      expect(
        Buffer.from(m![1]!, 'base64').equals(fs.readFileSync(path.join(FOLDER, names[i]!))),
      ).toBe(true);
    });
  });

  test('the joint states are the stored samples, in joint units', async () => {
    const stored = await storedAngles();
    const states = on(`/${ARM}/joint_states`);
    expect(states.length).toBeGreaterThan(20);
    let moved = 0;
    for (const s of states) {
      const at = stored.get(Number(s.ns / 1000n));
      expect(at, `a stored sample at ${s.ns}`).toBeDefined();
      const joints = s.data.joints as { name: string; position: number }[];
      expect(joints.map((j) => j.name)).toEqual(profile.servos.map((sv) => sv.joint));
      joints.forEach((j, i) => {
        const servo = profile.servos[i]!;
        expect(j.position).toBeCloseTo(jointFromServo(servo, at!.get(servo.id)!), 12);
      });
      if (Math.abs(joints[0]!.position) > 0.1) moved++;
    }
    expect(moved).toBeGreaterThan(5);
  });

  test('the link transforms put every link where the chain FK does, within 0.1 mm', async () => {
    const built = chainFromUrdf(profile, URDF);
    const urdfJoints = parseUrdfJoints(URDF);
    if (!built.ok || !urdfJoints.ok) throw new Error('so101 chain does not build');
    const chain = built.chain;
    const childOf = new Map(urdfJoints.joints.map((j) => [j.name, j.child]));
    const stored = await storedAngles();
    const tf = on(`/${ARM}/tf`);
    const states = on(`/${ARM}/joint_states`);
    expect(tf).toHaveLength(states.length);
    const frames = createFkFrames(chain);
    const samples = [Math.floor(tf.length / 3), Math.floor((2 * tf.length) / 3), tf.length - 1];
    for (const k of samples) {
      const t = tf[k]!;
      const at = stored.get(Number(t.ns / 1000n))!;
      const q = chain.joints.map((j) =>
        jointFromServo(profile.servos[j.servoIndex]!, at.get(profile.servos[j.servoIndex]!.id)!),
      );
      chainFkFrames(chain, q, frames);
      const transforms = t.data.transforms as Transform[];
      chain.joints.forEach((j, i) => {
        const p = linkPosition(transforms, childOf.get(j.name)!, chain.baseLink);
        const fk = [0, 1, 2].map((c) => frames.points[3 * i + c]!);
        expect(Math.hypot(...p.map((v, c) => v * 1000 - fk[c]!)), j.name).toBeLessThan(0.1);
      });
      const tip = linkPosition(transforms, chain.tipLink, chain.baseLink);
      const fkTip = [frames.tip[12]!, frames.tip[13]!, frames.tip[14]!];
      expect(Math.hypot(...tip.map((v, c) => v * 1000 - fkTip[c]!))).toBeLessThan(0.1);
    }
  });

  test('joint targets: every joint, the commanded ones at their command', () => {
    const targets = on(`/${ARM}/targets`);
    expect(targets).toHaveLength(2);
    const last = targets[1]!.data.joints as { name: string; position: number }[];
    expect(last.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    const deg = (id: number, d: number) => jointFromServo(servoById(profile, id), d);
    expect(last[0]!.position).toBeCloseTo(deg(1, -15), 9);
    expect(last[1]!.position).toBeCloseTo(deg(2, -20), 9); // from the first command
    expect(last[5]!.position).toBeCloseTo(deg(6, 25), 9);
  });

  test('every topic the Foxglove layout reads is in the file, every joint it plots too', () => {
    const layout = readLayout();
    const { threeD, plot, log } = layoutPanels(layout);
    const read = layoutTopics(layout);
    expect(read.filter((t) => !exported.channels.has(t) && !liveOnly(t))).toEqual([]);

    // each plotted index is a joint in every message of its topic
    for (const p of plot.paths) {
      const [, topic, index] = /^(.+?)\.joints\[(\d+)\]\.position$/.exec(p.value)!;
      for (const m of on(topic!))
        expect((m.data.joints as unknown[]).length).toBeGreaterThan(Number(index));
    }
    expect(exported.channels.get(log.topicToRender)).toBe('foxglove.Log');
    // the 3D panel's URDF layer reads the description topic (a std_msgs/String source)
    const urdf = Object.values(threeD.layers).find((l) => l.layerId === 'foxglove.Urdf');
    expect(urdf).toMatchObject({ sourceType: 'topic', topic: `/${ARM}/robot_description` });
    expect(exported.channels.get(urdf!.topic!)).toBe('std_msgs/String');
    expect(exported.channels.get(`/${ARM}/tf`)).toBe('foxglove.FrameTransforms');
  });

  test('every /{arm}/… topic in the file is one the live server advertises, with its schema', () => {
    const live = new Map(armChannels(ARM).map(({ spec }) => [spec.topic, spec.schemaName]));
    const shared = [...exported.channels].filter(([t]) => t.startsWith(`/${ARM}/`));
    expect(shared.length).toBeGreaterThanOrEqual(5);
    for (const [topic, schema] of shared) expect([topic, live.get(topic)]).toEqual([topic, schema]);
  });
});

describe('an arm whose history holds no announcement', () => {
  test("the export asks the broker for the arm's retained announcement", async () => {
    const client = await connectAsync(broker().url);
    const raw = JSON.parse(fs.readFileSync(path.join(FOLDER, 'profile.json'), 'utf8')) as Profile;
    await client.publishAsync('arm/old1/profile', profileAnnouncement(raw.name, raw.title, raw), {
      retain: true,
      qos: 1,
    });
    await client.endAsync();
    // a range that ended before the middleware saw (and stored) that announcement
    const e = await exportAs(
      'old1',
      new Date(Date.now() - 3600_000),
      new Date(Date.now() - 60_000),
    );
    expect(e.stderr).toContain('profile so101 (as the arm announces it on the broker');
    expect(e.metadata.get('profileSource')).toBe('broker');
    expect(e.messages.map((m) => m.topic)).toEqual(['/old1/robot_description']);
  });
});

interface Transform {
  parent_frame_id: string;
  child_frame_id: string;
  translation: { x: number; y: number; z: number };
  rotation: { x: number; y: number; z: number; w: number };
}
const servoById = (p: Profile, id: number) => p.servos.find((s) => s.id === id)!;

/** A link's origin in `root`'s frame (m), composing the message's parent → child transforms. */
function linkPosition(
  transforms: Transform[],
  link: string,
  root: string,
): [number, number, number] {
  const byChild = new Map(transforms.map((t) => [t.child_frame_id, t]));
  let p: [number, number, number] = [0, 0, 0];
  let frame = link;
  while (frame !== root) {
    const t = byChild.get(frame);
    if (!t) throw new Error(`no transform to ${frame}`);
    const { x, y, z, w } = t.rotation;
    const [vx, vy, vz] = p;
    // v + 2w(q×v) + 2q×(q×v)
    const cx = y * vz - z * vy;
    const cy = z * vx - x * vz;
    const cz = x * vy - y * vx;
    p = [
      vx + 2 * (w * cx + (y * cz - z * cy)) + t.translation.x,
      vy + 2 * (w * cy + (z * cx - x * cz)) + t.translation.y,
      vz + 2 * (w * cz + (x * cy - y * cx)) + t.translation.z,
    ];
    frame = t.parent_frame_id;
  }
  return p;
}
