/**
 * Cameras and plans in Foxglove, the channels beyond the arm's own reports.
 *
 * Cameras: `armtwin up --camera testsrc --foxglove PORT --users …` (a real ffmpeg
 * test source on the camera server, log-ins on). Foxglove's npm client (`@foxglove/ws-protocol`)
 * logged in as a viewer finds the camera as `/{arm}/camera/{cam}`, `foxglove.CompressedImage`,
 * and receives JPEG frames that ffmpeg decodes to the source's 640×480, with advancing time
 * stamps. The stream is read with each client's own log-in: a device account of another arm,
 * which the camera server does not let watch this arm, gets the camera's refusal and no frame.
 *
 * Plans: an operator's plan-only motion request (`arm/{arm}/request`, `targets: ["ready"]`) is
 * planned by the arm, which tells it on `arm/{arm}/feedback`; the viewer's `/{arm}/plan` gets its
 * end pose, the profile's `ready` pose in joint units (within the feedback's 1 µs rounding), and
 * `/{arm}/plan_tf` the arm drawn there as `plan/…` frames hung off the arm's root.
 *
 * The layout: every topic it reads (3D, plan layer, plots, log, the camera's Image panel) is
 * advertised by the live server.
 */
import { spawnSync } from 'node:child_process';
import mqtt from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { jointFromServo } from '@armtwin/robot';
import { freePorts } from '../helpers/services.ts';
import { NpmFoxglove, type Received } from '../helpers/foxglove.ts';
import { layoutPanels, layoutTopics, readLayout } from '../helpers/foxglove-layout.ts';
import { USERS_FILE } from './auth-cases.ts';
import { ARMTWIN, startUpProcess, type Child } from './sim-helpers.ts';

const TOPIC = '/arm1/camera/demo';
const N = 8;
let up: Child;
let url = '';
let mqttUrl = '';
const clients: NpmFoxglove[] = [];

beforeAll(async () => {
  const [httpPort = 0, mqttPort = 0, foxPort = 0] = await freePorts(3);
  up = await startUpProcess(
    [ARMTWIN, 'up'],
    [
      '--no-middleware',
      '--no-web',
      '--users',
      USERS_FILE,
      '--camera',
      'testsrc',
      '--foxglove',
      String(foxPort),
    ],
    { httpPort, mqttPort },
  );
  url = `ws://127.0.0.1:${foxPort}`;
  mqttUrl = `mqtt://127.0.0.1:${mqttPort}`;
}, 60_000);

afterAll(async () => {
  for (const c of clients) c.close();
  await up?.stop();
});

const connect = async (user: string) => {
  const c = await NpmFoxglove.connect(url, user);
  clients.push(c);
  return c;
};

const ms = (m: Received) => {
  const t = m.body.timestamp as { sec: number; nsec: number };
  return t.sec * 1000 + t.nsec / 1e6;
};

/** ffmpeg's decoding of one JPEG to 8-bit grey: its byte count is width × height. */
function decodedBytes(jpeg: Buffer): number {
  const r = spawnSync(
    'ffmpeg',
    [
      '-v',
      'error',
      '-f',
      'jpeg_pipe',
      '-i',
      'pipe:0',
      '-f',
      'rawvideo',
      '-pix_fmt',
      'gray',
      'pipe:1',
    ],
    { input: jpeg, maxBuffer: 16 * 1024 * 1024 },
  );
  expect(r.stderr.toString()).toBe('');
  expect(r.status).toBe(0);
  return r.stdout.length;
}

describe('cameras as foxglove.CompressedImage', () => {
  test('a viewer receives decodable JPEG frames with advancing time stamps', async () => {
    const viewer = await connect('viewer');
    const channel = await viewer.until(() => viewer.channels.get(TOPIC), 'the camera channel');
    expect(channel.schemaName).toBe('foxglove.CompressedImage');
    const frames = await viewer.subscribe(TOPIC);
    // a test source at 30 frames/s; under a loaded machine ffmpeg may lag: time, not speed, is not
    // what is tested here, so the wait is long and what did come is told if it runs out
    await viewer
      .until(() => frames.length >= N, `${N} frames`, 30_000)
      .catch((err: Error) => {
        throw new Error(
          `${err.message}: ${frames.length} came, ${JSON.stringify(viewer.statuses)}`,
        );
      });
    for (const f of frames.slice(0, N)) {
      expect(f.body).toMatchObject({ format: 'jpeg', frame_id: 'arm1/camera/demo' });
      expect(Number(f.ns / 1_000_000n)).toBe(Math.floor(ms(f)));
    }
    const jpegs = frames.slice(0, N).map((f) => Buffer.from(f.body.data as string, 'base64'));
    for (const j of jpegs)
      expect([j[0], j[1], j.at(-2), j.at(-1)]).toEqual([0xff, 0xd8, 0xff, 0xd9]);
    expect(decodedBytes(jpegs[0]!)).toBe(640 * 480);
    expect(decodedBytes(jpegs[N - 1]!)).toBe(640 * 480);
    // the test source moves: the pictures differ; the stamps advance (two frames ffmpeg hands over
    // in one read may share a millisecond)
    expect(new Set(jpegs.map((j) => j.toString('base64'))).size).toBeGreaterThan(1);
    const stamps = frames.slice(0, N).map(ms);
    for (let i = 1; i < stamps.length; i++)
      expect(stamps[i]!).toBeGreaterThanOrEqual(stamps[i - 1]!);
    expect(stamps.at(-1)!).toBeGreaterThan(stamps[0]!);
  });

  test('a user the camera server does not let watch this arm gets its refusal, no frame', async () => {
    const other = await connect('arm2'); // the device account of arm2
    const frames = await other.subscribe(TOPIC);
    const status = await other.until(
      () => other.statuses.find((s) => s.message.includes('camera')),
      "the camera's refusal",
    );
    expect(status.message).toMatch(/403/);
    expect(frames).toEqual([]);
  });
});

describe('plans: /{arm}/plan and /{arm}/plan_tf', () => {
  test("a plan-only request's end pose, as the arm planned it, and the arm drawn there", async () => {
    const { profile } = readRobotFolder('armtwin5');
    const viewer = await connect('viewer');
    const plan = await viewer.subscribe('/arm1/plan');
    const planTf = await viewer.subscribe('/arm1/plan_tf');
    const op = await mqtt.connectAsync(mqttUrl, {
      username: 'operator',
      password: 'operator-demo',
      reconnectPeriod: 0,
    });
    const request = { id: 'fox-plan', mode: 'joint', targets: ['ready'] };
    await op.publishAsync('arm/arm1/request', JSON.stringify(request), { qos: 1 });
    await op.endAsync();
    const [p] = await viewer.until(() => plan.length > 0 && plan, 'the plan');
    expect(p!.body).toMatchObject({ id: 'fox-plan', status: 'planned', mode: 'joint' });
    const joints = p!.body.joints as { name: string; position: number }[];
    expect(joints.map((j) => j.name)).toEqual(profile.servos.map((s) => s.joint));
    const ready = profile.poses.ready!; // servo degrees, servo order; NaN: left where it is
    profile.servos.forEach((s, i) => {
      if (Number.isNaN(ready[i])) return; // the gripper: not in the pose
      const deg = Math.abs(jointFromServo(s, ready[i]!) - joints[i]!.position) * (180 / Math.PI);
      expect(deg).toBeLessThan(0.15); // 1 µs of the feedback's rounding is 0.135° here
    });
    const [tf] = await viewer.until(() => planTf.length > 0 && planTf, 'the plan transforms');
    type T = { parent_frame_id: string; child_frame_id: string };
    const transforms = tf!.body.transforms as T[];
    expect(transforms[0]).toMatchObject({
      child_frame_id: `plan/${transforms[0]!.parent_frame_id}`,
    });
    expect(transforms.slice(1).every((t) => t.child_frame_id.startsWith('plan/'))).toBe(true);
    // the layout's plan layer draws these frames: its prefix is theirs
    const layers = Object.values(layoutPanels(readLayout()).threeD.layers);
    expect(layers.find((l) => l.framePrefix === 'plan/')).toMatchObject({
      layerId: 'foxglove.Urdf',
      topic: '/arm1/robot_description',
    });
  });
});

describe('the layout deploy/foxglove/armtwin-arm.json, live', () => {
  test('every topic it reads is advertised, the camera its Image panel shows included', async () => {
    const viewer = await connect('viewer');
    const read = layoutTopics(readLayout());
    expect(read).toContain(TOPIC);
    await viewer.until(
      () => read.every((t) => viewer.channels.has(t)),
      'every topic of the layout',
    );
  });
});
