/**
 * `armtwin gateway --ros2` follows its profile file as the bus gateway does (@armtwin/gateway's
 * `followProfile`): a keep-out zone saved from the HUD (`PUT /api/robots/<name>/keep-out` on a
 * real `armtwin up`, which writes the robot's profile.json) is announced again and in force on the
 * ROS 2 arm without a restart: a move into it is refused and the arm (the test node on real rclpy
 * and FastDDS, standing in for ros2_control) stays where it was; the zone taken away, the same
 * move runs.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import type { Ros2Bridge } from '@armtwin/ros2';
import { MODELS_DIR } from '@armtwin/sim';
import { freePorts } from '../helpers/services.ts';
import { startRos2Side, startTestArm, testDomain } from '../helpers/ros2.ts';
import { armtwin, startUpProcess, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'ros-zone';
const JOINTS = ['base_yaw', 'shoulder', 'elbow', 'wrist_pitch', 'wrist_roll', 'gripper'];
const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** armtwin5's shoulder, elbow and wrist at −45°, −45°, −90°: the hand straight down into the table. */
const INTO_TABLE = '{#001A-045.00T0500!#002A-045.00T0500!#003A-090.00T0500!}';
/** The shoulder's joint there, rad (armtwin5: offset 0, polarity 1). */
const SHOULDER_IN_TABLE = -45 * (Math.PI / 180);
const domain = testDomain();

let up: Child;
let rosArm: Awaited<ReturnType<typeof startTestArm>>;
let ros: Ros2Bridge;
let gateway: Child;
let w: StatusWatcher;
let models = '';
let httpPort = 0;
/** The test node's latest joint positions (rad), by joint name, as a ROS 2 subscriber sees them. */
const joints = new Map<string, number>();

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-ros2-follow-'));
  const file = path.join(models, 'zone5', 'profile.json');
  fs.cpSync(path.join(MODELS_DIR, 'armtwin5'), path.join(models, 'zone5'), { recursive: true });
  fs.writeFileSync(
    file,
    JSON.stringify({ ...JSON.parse(fs.readFileSync(file, 'utf8')), name: 'zone5' }),
  );
  const [h = 0, m = 0] = await freePorts(2);
  httpPort = h;
  up = await startUpProcess(
    ['scripts/start.mjs'],
    ['--no-middleware', '--no-web', '--models', models],
    { httpPort, mqttPort: m },
  );
  const url = `mqtt://127.0.0.1:${m}`;
  w = await StatusWatcher.connect(url, ARM);
  await w.client.subscribeAsync(`arm/${ARM}/profile`, { qos: 1 });
  rosArm = await startTestArm(['--joints', JOINTS.join(','), '--domain', String(domain)]);
  ros = await startRos2Side(domain);
  await ros.subscribe('/joint_states', 'joint_state', (msg) =>
    msg.name.forEach((n, i) => joints.set(n, msg.position[i]!)),
  );
  gateway = armtwin([
    ...['gateway', '--ros2', '--domain', String(domain), '--mqtt', url, '--arm', ARM],
    ...['--profile', 'zone5', '--models', models],
  ]);
  await w
    // a bound, not a timing: the gateway's start (Node, its rclpy process, DDS discovery) once
    // took over 30 s here, at load 28 on 2 cores
    .until(() => (w.retained.get(`arm/${ARM}/online`) === '1' ? true : undefined), 60_000, 'online')
    .catch((err: Error) => {
      throw new Error(`${err.message}\n${gateway.output()}`);
    });
});

afterAll(async () => {
  await gateway?.stop();
  await ros?.close();
  await rosArm?.stop();
  await w?.close();
  await up?.stop('SIGKILL');
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

const putZones = async (zones: unknown[]) => {
  const res = await fetch(`http://127.0.0.1:${httpPort}/api/robots/zone5/keep-out`, {
    method: 'PUT',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify({ zones }),
  });
  return { status: res.status, body: (await res.json()) as { ok: boolean } };
};
const announcedZones = () => {
  const a = w.retained.get(`arm/${ARM}/profile`);
  return a ? (JSON.parse(a).profile.keepOut?.zones as unknown[] | undefined) : undefined;
};
const jointNear = (name: string, rad: number, tol = 0.002) =>
  Math.abs((joints.get(name) ?? NaN) - rad) < tol ? true : undefined;

test('a zone saved from the HUD is in force on the ROS 2 arm at once, without a restart', async () => {
  expect(announcedZones() ?? []).toEqual([]);
  const pid = gateway.proc.pid;
  expect(await putZones([TABLE])).toMatchObject({ status: 200, body: { ok: true } });
  await w.until(() => (announcedZones()?.length === 1 ? true : undefined), 10_000, 'announced');
  expect(announcedZones()).toEqual([TABLE]);

  const from = w.items.length;
  await w.send(INTO_TABLE);
  const err = await w.frame((f) => f.type === 'controllerError', from);
  expect(err.frame).toMatchObject({
    text: expect.stringMatching(/^group rejected: zone: hand in "table"/),
  });
  // A harmless move after it runs; by then the refused one would have moved the shoulder.
  await w.send('#004P1600T0200!');
  const roll = (((1600 - 1500) * 270) / 2000) * (Math.PI / 180);
  await w.until(() => jointNear('wrist_roll', roll), 15_000, 'the wrist roll moved in ROS 2');
  expect(jointNear('shoulder', 0)).toBe(true);

  expect(gateway.proc.pid).toBe(pid);
  expect(gateway.proc.exitCode).toBeNull();
  expect(gateway.output()).toMatch(/profile file changed: new limits and zones in force/);
});

test('the zone taken away again, the same move runs on the ROS 2 arm', async () => {
  const before = w.retained.get(`arm/${ARM}/profile`);
  expect(await putZones([])).toMatchObject({ status: 200, body: { ok: true } });
  await w.until(
    () => (w.retained.get(`arm/${ARM}/profile`) !== before ? true : undefined),
    10_000,
    'announced again',
  );
  expect(announcedZones() ?? []).toEqual([]);
  await w.send(INTO_TABLE);
  await w.until(
    () => jointNear('shoulder', SHOULDER_IN_TABLE),
    15_000,
    'the shoulder down at the table in ROS 2',
  );
});
