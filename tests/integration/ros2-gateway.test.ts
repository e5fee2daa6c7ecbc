/**
 * `armtwin gateway --ros2` against a ROS 2 arm on real rclpy and FastDDS (the test arm node,
 * python/armtwin_ros2/test_arm.py, stands in for ros2_control's joint_trajectory_controller and
 * joint_state_broadcaster) through a real Mosquitto: the arm's joint states reach MQTT as angle
 * frames within 0.01° (an extra joint ignored), a jog and a `$KMS` become trajectories the arm
 * executes, the arm goes offline when its joint states stop and online when they come back, and
 * a profile whose joints the arm lacks stops the gateway at start, naming them.
 */
import { afterAll, beforeAll, expect, test } from 'vitest';
import { parseSummary, type Frame } from '@armtwin/protocol';
import { startTestArm, testDomain } from '../helpers/ros2.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'ros-gw';
const JOINTS = ['base_yaw', 'shoulder', 'elbow', 'wrist_pitch', 'wrist_roll', 'gripper'];
const INITIAL = [0.1, -0.2, 0.3, -0.4, 0.5, 0.6]; // rad; armtwin5's offsets are 0
const DEG = 180 / Math.PI;
const broker = useMosquitto();
const domain = String(testDomain());

let rosArm: Awaited<ReturnType<typeof startTestArm>>;
let gateway: Child;
let w: StatusWatcher;

/** Servo angles (deg) of the latest full state group after item `from`. */
function latest(from = 0): number[] | undefined {
  for (let i = w.items.length - 1; i >= from; i--) {
    const it = w.items[i]!;
    if (!('group' in it) || it.group.frames.length !== JOINTS.length) continue;
    return it.group.frames.map((f) => (f.type === 'angle' ? f.deg : NaN));
  }
  return undefined;
}
const near = (deg: number[], i: number, want: number, tol: number) =>
  Math.abs(deg[i]! - want) < tol;

beforeAll(async () => {
  const url = broker().url;
  w = await StatusWatcher.connect(url, ARM);
  rosArm = await startTestArm([
    ...['--joints', [...JOINTS, 'wheel'].join(','), '--initial', [...INITIAL, 7].join(',')],
    ...['--domain', domain, '--rate', '50'],
  ]);
  gateway = armtwin(['gateway', '--ros2', '--domain', domain, '--mqtt', url, '--arm', ARM]);
  await w
    .until(() => latest(), 30_000, 'state groups from the gateway')
    .catch((err: Error) => {
      throw new Error(`${err.message}\n${gateway.output()}`);
    });
});

afterAll(async () => {
  await gateway?.stop();
  await rosArm?.stop();
  await w?.close();
});

test('the arm’s joint states reach MQTT as angle frames within 0.01°, an extra joint ignored', () => {
  const deg = latest()!;
  INITIAL.forEach((q, i) => expect(Math.abs(deg[i]! - q * DEG)).toBeLessThan(0.01));
  expect(w.retained.get(`arm/${ARM}/online`)).toBe('1');
  expect(gateway.output()).toMatch(/joints not in the profile, ignored: wheel/);
});

test('its summary on arm/{id}/summary: the joint states as servo angles, to 0.1°', async () => {
  const topic = `arm/${ARM}/summary`;
  await w.client.subscribeAsync(topic, { qos: 0 });
  const s = await w.until(
    () => {
      const r = parseSummary(w.retained.get(topic) ?? '');
      return r.ok ? r.summary : undefined;
    },
    5000,
    'a summary',
  );
  expect(s.joints.map((j) => j.deg)).toEqual(INITIAL.map((q) => Math.round(q * DEG * 10) / 10));
  expect([s.state, s.holder]).toEqual(['still', null]);
});

test('a jog (a timed pulse move) becomes a trajectory the arm executes', async () => {
  const from = w.items.length;
  await w.send('#001P1600T0400!'); // servo angle (1600 − 1500) · 270 / 2000 = 13.5°
  await w.until(
    () => {
      const deg = latest(from);
      return deg && near(deg, 1, 13.5, 0.01) ? true : undefined;
    },
    15_000,
    'the shoulder at 13.5°',
  );
  expect(near(latest()!, 0, INITIAL[0]! * DEG, 0.01)).toBe(true); // the others stay
});

test('$KMS is solved by the controller and executed as a trajectory', async () => {
  const from = w.items.length;
  const before = latest()!;
  await w.send('$KMS:150,0,250,500!');
  const reply = await w.frame((f: Frame) => f.type === 'kmsResult', from, 15_000);
  expect(reply.frame).toMatchObject({ code: 0 });
  await w.until(
    () => {
      const deg = latest(from);
      return deg && !near(deg, 1, before[1]!, 1) ? true : undefined;
    },
    15_000,
    'the arm moving to the $KMS target',
  );
});

test('the arm goes offline when its joint states stop, and online when they come back', async () => {
  rosArm.pause();
  await w.until(
    () => (w.retained.get(`arm/${ARM}/online`) === '0' ? true : undefined),
    15_000,
    'offline',
  );
  const from = w.items.length;
  await w.send('#002P1600T0300!');
  const refused = await w.frame((f: Frame) => f.type === 'controllerError', from, 15_000);
  expect(refused.frame).toMatchObject({ text: expect.stringContaining('no joint states') });
  rosArm.resume();
  await w.until(
    () => (w.retained.get(`arm/${ARM}/online`) === '1' ? true : undefined),
    15_000,
    'online again',
  );
});

test('a profile whose joints the arm lacks stops the gateway at start, naming them', async () => {
  const wrong = armtwin([
    ...['gateway', '--ros2', '--domain', domain, '--profile', 'track6'],
    ...['--mqtt', broker().url, '--arm', 'ros-gw-wrong'],
  ]);
  const code = await new Promise<number | null>((resolve) => wrong.proc.once('exit', resolve));
  expect(code).not.toBe(0);
  expect(wrong.output()).toMatch(/has no joint .* of profile track6/);
});
