/**
 * `armtwin up --foxglove PORT` with log-ins, against both real Foxglove clients: npm
 * `@foxglove/ws-protocol`'s FoxgloveClient (foxglove.websocket.v1, Lichtblick's) and a Python
 * foxglove.sdk.v1 client (Foxglove's, foxglove_bridge ≥ 3.2's). Each sees the arm's channels and
 * services, and receives joint states equal to the simulator's MQTT reports of the same `$TIM`
 * (within 0.01°) and link transforms whose base → tip pose is the chain's FK of those reports
 * (within 0.1 mm). The robot description names its meshes as package:// assets the server
 * serves. A viewer's publish is refused and moves nothing; the holder's jog moves the simulated
 * arm; the stop service stops a jog short of its target.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { chainFk, createMat4, mat4Multiply, type Mat4 } from '@armtwin/ik';
import { readRobotFolder, MODELS_DIR } from '@armtwin/motion/robot-folder';
import { chainFromUrdf, jointFromServo, servoFromPwm } from '@armtwin/robot';
import { freePorts } from '../helpers/services.ts';
import { NpmFoxglove, sdkClient } from '../helpers/foxglove.ts';
import { USERS_FILE } from './auth-cases.ts';
import { ARMTWIN, startUpProcess, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'arm1';
const folder = readRobotFolder('armtwin5');
const { profile } = folder;
const urdf = fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', profile.urdf), 'utf8');
const built = chainFromUrdf(profile, urdf);
if (!built.ok) throw new Error(built.errors.join('; '));
const chain = built.chain;
const DEG = 180 / Math.PI;

let up: Child;
let watcher: StatusWatcher;
let url = '';
const clients: NpmFoxglove[] = [];

beforeAll(async () => {
  const [httpPort = 0, mqttPort = 0, foxPort = 0] = await freePorts(3);
  up = await startUpProcess(
    [ARMTWIN, 'up'],
    ['--no-middleware', '--no-web', '--users', USERS_FILE, '--foxglove', String(foxPort)],
    { httpPort, mqttPort },
  );
  url = `ws://127.0.0.1:${foxPort}`;
  watcher = await StatusWatcher.connect(`mqtt://127.0.0.1:${mqttPort}`, ARM, {
    username: 'viewer',
    password: 'viewer-demo',
  });
  await watcher.client.subscribeAsync([`arm/${ARM}/holder`, `arm/${ARM}/audit`], { qos: 1 });
  await watcher.online();
}, 60_000);

afterAll(async () => {
  for (const c of clients) c.close();
  await watcher?.client.endAsync();
  await up?.stop();
});

const connect = async (user?: string) => {
  const c = await NpmFoxglove.connect(url, user);
  clients.push(c);
  return c;
};

/** Each servo's pulse width in the MQTT report stamped `ms`, or undefined if none is seen. */
function reportAt(ms: number): number[] | undefined {
  const pwm = profile.servos.map((s) => watcher.positions(s.id).find(([t]) => t === ms)?.[1]);
  return pwm.every((p) => p !== undefined) ? (pwm as number[]) : undefined;
}

const msOf = (ns: bigint | string) => Number(BigInt(ns) / 1_000_000n);

const holder = () =>
  (JSON.parse(watcher.retained.get(`arm/${ARM}/holder`) ?? '{}') as { user?: string }).user;

/** Whether servo `id` moved more than `us` from `start` in a report after item `from`. */
const moved = (id: number, from: number, start: number, us: number) =>
  watcher.positions(id, from).some(([, p]) => Math.abs(p - start) > us) || undefined;

/** Joint states equal the simulator's report of the same stamp, within 0.01°. */
function expectJointStatesMatch(
  messages: { ns: bigint | string; body: Record<string, unknown> }[],
) {
  let compared = 0;
  for (const m of messages) {
    const pwm = reportAt(msOf(m.ns));
    expect(pwm, `an MQTT report stamped ${msOf(m.ns)}`).toBeDefined();
    const joints = m.body.joints as { name: string; position: number }[];
    expect(joints.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    profile.servos.forEach((s, i) => {
      const reported = jointFromServo(s, servoFromPwm(s, pwm![i]!)) * DEG;
      expect(Math.abs(joints[i]!.position * DEG - reported)).toBeLessThan(0.01);
    });
    compared++;
  }
  expect(compared).toBeGreaterThan(0);
}

/** A Foxglove transform as a column-major 4×4 in mm. */
function mat4Of(t: {
  translation: Record<string, number>;
  rotation: Record<string, number>;
}): Mat4 {
  const { x, y, z, w } = t.rotation as { x: number; y: number; z: number; w: number };
  const m = createMat4();
  // prettier-ignore
  m.set([
    1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w), 0,
    2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w), 0,
    2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y), 0,
    t.translation.x! * 1000, t.translation.y! * 1000, t.translation.z! * 1000, 1,
  ]);
  return m;
}

/** Link transforms compose, base → tip, to the chain's FK of the report of the same stamp. */
function expectTransformsMatchFk(
  messages: { ns: bigint | string; body: Record<string, unknown> }[],
) {
  for (const m of messages) {
    type T = {
      parent_frame_id: string;
      child_frame_id: string;
      translation: Record<string, number>;
      rotation: Record<string, number>;
    };
    const byChild = new Map((m.body.transforms as T[]).map((t) => [t.child_frame_id, t]));
    let pose = createMat4();
    pose.set([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);
    for (let link = chain.tipLink; link !== chain.baseLink;) {
      const t = byChild.get(link);
      expect(t, `a transform to ${link}`).toBeDefined();
      pose = mat4Multiply(createMat4(), mat4Of(t!), pose);
      link = t!.parent_frame_id;
    }
    const pwm = reportAt(msOf(m.ns));
    expect(pwm).toBeDefined();
    const q = chain.joints.map((j) => {
      const s = profile.servos[j.servoIndex]!;
      return jointFromServo(s, servoFromPwm(s, pwm![j.servoIndex]!));
    });
    const fk = chainFk(chain, q);
    const mm = Math.hypot(fk[12]! - pose[12]!, fk[13]! - pose[13]!, fk[14]! - pose[14]!);
    expect(mm).toBeLessThan(0.1);
  }
}

const CHANNELS = ['joint_states', 'targets', 'tf', 'robot_description', 'health', 'log'].map(
  (k) => `/${ARM}/${k}`,
);

describe('foxglove.websocket.v1: npm @foxglove/ws-protocol', () => {
  test('a logged-in viewer sees the channels and services; no log-in is refused', async () => {
    await expect(NpmFoxglove.connect(url)).rejects.toThrow(/401/);
    const viewer = await connect('viewer');
    expect(viewer.ws.protocol).toBe('foxglove.websocket.v1');
    await viewer.until(() => CHANNELS.every((t) => viewer.channels.has(t)), 'the channels');
    expect(viewer.channels.get(`/${ARM}/tf`)?.schemaName).toBe('foxglove.FrameTransforms');
    expect(viewer.channels.get(`/${ARM}/log`)?.schemaName).toBe('foxglove.Log');
    await viewer.until(() => viewer.services.has(`/${ARM}/stop`), 'the stop service');
  });

  test('the robot description names its meshes as package:// assets the server serves', async () => {
    const viewer = await connect('viewer');
    const got = await viewer.subscribe(`/${ARM}/robot_description`);
    const [m] = await viewer.until(() => got.length > 0 && got, 'the URDF');
    const text = (m!.body as { data: string }).data;
    expect(text).toContain('filename="package://armtwin5/meshes/base.stl"');
    const asset = await new Promise<Uint8Array>((resolve, reject) => {
      viewer.client.on('fetchAssetResponse', (r) =>
        r.status === 0
          ? resolve(new Uint8Array(r.data.buffer, r.data.byteOffset, r.data.byteLength))
          : reject(new Error(r.error)),
      );
      viewer.client.fetchAsset('package://armtwin5/meshes/base.stl', 1);
    });
    expect(
      Buffer.from(asset).equals(
        fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'meshes', 'base.stl')),
      ),
    ).toBe(true);
  });

  test("a viewer's publish and stop are refused, and the arm stays where it was", async () => {
    const viewer = await connect('viewer');
    const before = watcher.items.length;
    viewer.publish(`/${ARM}/jog`, { joint: 'base_yaw', delta: 0.5, ms: 500 });
    const status = await viewer.until(
      () => viewer.statuses.find((s) => /viewer/.test(s.message)),
      'a refusal',
    );
    expect(status.message).toMatch(/refused: viewer is a viewer/);
    expect(await viewer.call(`/${ARM}/stop`)).toEqual({
      ok: false,
      body: expect.stringMatching(/viewers only watch/),
    });
    await new Promise((r) => setTimeout(r, 800));
    const base = watcher.positions(0, before).map(([, p]) => p);
    expect(new Set(base).size).toBe(1);
  });

  test("the holder's jog moves the arm, and both clients see it move as the arm reports it", async () => {
    const op = await connect('operator');
    const states = await op.subscribe(`/${ARM}/joint_states`);
    const tf = await op.subscribe(`/${ARM}/tf`);
    const targets = await op.subscribe(`/${ARM}/targets`);
    expect((await op.call(`/${ARM}/take`)).ok).toBe(true);
    await watcher.until(() => holder() === 'operator' || undefined, 10_000, 'operator holds arm1');
    const start = watcher.positions(1).at(-1)![1];
    const from = watcher.items.length;
    const jogAt = Date.now();
    // the shoulder: the tip swings off the base's axis, so the transforms' rotations count
    op.publish(`/${ARM}/jog`, { joint: 'shoulder', delta: 0.6, ms: 3000 });
    await watcher.until(() => moved(1, from, start, 40), 10_000, 'shoulder moving');
    const sdk = await sdkClient(url, 'viewer', { [`/${ARM}/joint_states`]: 5, [`/${ARM}/tf`]: 5 });
    // the jog runs to its end: about 0.6 rad × 2000 µs / 270° ≈ 255 µs
    await watcher.until(() => moved(1, from, start, 230), 15_000, 'the jog done');
    const movingStates = states.filter((m) => msOf(m.ns) >= jogAt).slice(0, 40);
    const shoulder = movingStates.map(
      (m) => (m.body.joints as { position: number }[])[1]!.position,
    );
    expect(new Set(shoulder).size).toBeGreaterThan(3);
    expectJointStatesMatch(movingStates);
    expectTransformsMatchFk(tf.filter((m) => msOf(m.ns) >= jogAt).slice(0, 40));
    expect(targets.some((t) => t.body.by === 'operator')).toBe(true);
    // …and the sdk.v1 client
    expect(sdk.protocol).toBe('foxglove.sdk.v1');
    expect(sdk.channels).toEqual(expect.arrayContaining(CHANNELS));
    expectJointStatesMatch(sdk.messages[`/${ARM}/joint_states`]!);
    expectTransformsMatchFk(sdk.messages[`/${ARM}/tf`]!);
  });

  test('the stop service stops a jog short of its target', async () => {
    const op = await connect('operator');
    const log = await op.subscribe(`/${ARM}/log`);
    if (holder() !== 'operator') expect((await op.call(`/${ARM}/take`)).ok).toBe(true);
    await watcher.until(() => holder() === 'operator' || undefined, 10_000, 'operator holds arm1');
    const start = watcher.positions(0).at(-1)![1];
    const from = watcher.items.length;
    // base_yaw −1.2 rad (about 509 µs) in 4 s; stopped as soon as it moves
    op.publish(`/${ARM}/jog`, { joint: 'base_yaw', delta: -1.2, ms: 4000 });
    await watcher.until(() => moved(0, from, start, 40), 10_000, 'base moving');
    expect((await op.call(`/${ARM}/stop`)).ok).toBe(true);
    await op.until(
      () => log.some((l) => /^e-stop/.test(String(l.body.message))),
      'the e-stop in the log',
    );
    await new Promise((r) => setTimeout(r, 600));
    const after = watcher
      .positions(0)
      .slice(-5)
      .map(([, p]) => p);
    expect(new Set(after).size).toBe(1); // standing
    expect(Math.abs(after[0]! - start)).toBeLessThan(400);
  });
});
