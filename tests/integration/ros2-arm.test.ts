/**
 * `armtwin ros2`: an armtwin arm (`armtwin sim`, a real Mosquitto) seen and driven from ROS 2
 * through real rclpy and FastDDS. The ROS 2 side of the test is a node of its own (a bridge
 * process, as any ROS 2 program would subscribe and publish): it sees the arm's joint states in
 * radians under the URDF's joint names, equal to the MQTT status within 0.01°, and the latched
 * robot description (the profile's URDF, received by a subscriber that joins late); a trajectory
 * moves the arm while the bridge holds it, and does not once someone else holds it (the
 * controller refuses it, audited as the bridge's user).
 */
import fs from 'node:fs';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { jointFromPwm, parseProfile, type Profile } from '@armtwin/robot';
import { parseAudit, parseHolder, type AuditEvent } from '@armtwin/protocol';
import type { JointStateMsg, Ros2Bridge } from '@armtwin/ros2';
import { REPO_ROOT } from '../helpers/services.ts';
import { startRos2Side, testDomain } from '../helpers/ros2.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'ros-arm';
const NS = '/armtwin/ros_arm';
const MODEL = path.join(REPO_ROOT, 'public', 'models', 'armtwin5');
const DEG = 180 / Math.PI;
const broker = useMosquitto();
const domain = testDomain();

let profile: Profile;
let sim: Child;
let bridge: Child;
let ros: Ros2Bridge;
let watch: StatusWatcher;
let other: MqttClient;
const states: JointStateMsg[] = [];
const audits: AuditEvent[] = [];
let holder: string | null | undefined;

/**
 * The arm's position report of every servo as joint values (rad): the latest full group, or the
 * pose the status topic says at the payload stamped `time` (`$TIM`, which the bridge puts in the
 * JointState's header): every position frame up to that payload, the newest per servo, as the
 * bridge folds them (a payload that moves one servo is a joint state too).
 */
function mqttJoints(time?: number): number[] | undefined {
  if (time === undefined) {
    for (let i = watch.items.length - 1; i >= 0; i--) {
      const it = watch.items[i]!;
      if (!('group' in it)) continue;
      const pos = it.group.frames.filter((f) => f.type === 'position');
      if (pos.length === profile.servos.length)
        return jointsOf(new Map(pos.map((f) => [f.id, f.pwm])));
    }
    return undefined;
  }
  const pwm = new Map<number, number>();
  let found = false;
  for (const it of watch.items) {
    if (found && it.time !== time) break;
    const frames = 'group' in it ? it.group.frames : [it.frame];
    for (const f of frames) if (f.type === 'position') pwm.set(f.id, f.pwm);
    if (it.time === time) found = true;
  }
  return found ? jointsOf(pwm) : undefined;
}

function jointsOf(pwm: ReadonlyMap<number, number>): number[] | undefined {
  if (!profile.servos.every((s) => pwm.has(s.id))) return undefined;
  return profile.servos.map((s) => jointFromPwm(s, pwm.get(s.id)!));
}

/** The pose, once the last 10 position groups are all the same. */
function atRest(): number[] | undefined {
  const poses: string[] = [];
  for (const it of watch.items.slice(-40)) {
    if (!('group' in it)) continue;
    const pos = it.group.frames.map((f) => (f.type === 'position' ? `${f.id}:${f.pwm}` : ''));
    if (pos.some(Boolean)) poses.push(pos.join());
  }
  const last = poses.slice(-10);
  return last.length === 10 && new Set(last).size === 1 ? mqttJoints() : undefined;
}

beforeAll(async () => {
  const parsed = parseProfile(
    JSON.parse(fs.readFileSync(path.join(MODEL, 'profile.json'), 'utf8')),
  );
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  profile = parsed.profile;
  const url = broker().url;
  watch = await StatusWatcher.connect(url, ARM);
  other = await mqtt.connectAsync(url);
  other.on('message', (topic, payload) => {
    if (topic.endsWith('/holder')) holder = parseHolder(payload)?.user;
    else {
      const a = parseAudit(payload);
      if (a) audits.push(a);
    }
  });
  await other.subscribeAsync([`arm/${ARM}/holder`, `arm/${ARM}/audit`], { qos: 1 });
  ros = await startRos2Side(domain);
  await ros.subscribe(`${NS}/joint_states`, 'joint_state', (m) => states.push(m));
  sim = armtwin(['sim', '--mqtt', url, '--arm', ARM, '--rate', '50']);
  await watch.until(() => mqttJoints(), 20_000, 'the simulated arm');
  bridge = armtwin(['ros2', '--mqtt', url, '--arm', ARM, '--domain', String(domain), '--take']);
  await watch
    .until(() => (holder === 'ros2' ? true : undefined), 30_000, 'the bridge to hold the arm')
    .catch((err: Error) => {
      throw new Error(`${err.message}\n${bridge.output()}`);
    });
});

afterAll(async () => {
  await bridge?.stop();
  await sim?.stop();
  await ros?.close();
  await watch?.close();
  await other?.endAsync(true);
});

/** Sends a trajectory from ROS 2 once the bridge's subscription is matched. */
async function sendTrajectory(
  names: string[],
  points: { positions: number[]; time_from_start_ms: number }[],
) {
  const topic = `${NS}/joint_trajectory`;
  expect(await ros.advertise(topic, 'joint_trajectory', { waitMs: 10_000 })).toBeGreaterThan(0);
  ros.publish(topic, 'joint_trajectory', { joint_names: names, points });
}

test('a late ROS 2 subscriber gets the robot description: the profile URDF, latched', async () => {
  let urdf: string | undefined;
  await ros.subscribe(`${NS}/robot_description`, 'string', (m) => (urdf = m.data), {
    durable: true,
  });
  const got = await watch.until(() => urdf, 15_000, 'robot_description');
  expect(got).toBe(fs.readFileSync(path.join(MODEL, profile.urdf), 'utf8'));
});

test("the holder's trajectory moves the arm, and ROS 2 sees its joint states as the MQTT status says (0.01°)", async () => {
  await sendTrajectory(
    ['shoulder', 'elbow'],
    [
      { positions: [-0.3, -0.6], time_from_start_ms: 500 },
      { positions: [-0.5, -1.0], time_from_start_ms: 1000 },
    ],
  );
  const at = await watch.until(
    () => {
      const q = mqttJoints();
      return q && Math.abs(q[1]! + 0.5) * DEG < 0.2 && Math.abs(q[2]! + 1.0) * DEG < 0.2
        ? q
        : undefined;
    },
    15_000,
    'the arm at the trajectory end',
  );
  expect(Math.abs(at[0]!) * DEG).toBeLessThan(0.2); // base, not named, stayed
  // The ROS 2 joint state carries the values of the MQTT status payload with its stamp.
  const n = states.length;
  const js = await watch.until(
    () => (states.length > n ? states.at(-1) : undefined),
    10_000,
    'a joint state',
  );
  expect(js.name).toEqual(profile.servos.map((s) => s.joint));
  // The bridge and this test's watcher are two MQTT subscribers: the watcher's copy of the
  // same report may come after the joint state made from it.
  const q = await watch.until(() => mqttJoints(js.stamp_ms), 10_000, 'the report of that stamp');
  js.position.forEach((v, i) => expect(Math.abs(v - q[i]!) * DEG).toBeLessThan(0.01));
  expect(Math.abs(js.position[1]! + 0.5) * DEG).toBeLessThan(0.2);
});

test("someone else's hold: the bridge's trajectory does not move the arm and is refused as its user's", async () => {
  await other.publishAsync(`arm/${ARM}/override/alice`, 'take', { qos: 1 });
  await watch.until(() => (holder === 'alice' ? true : undefined), 10_000, 'alice to hold the arm');
  const before = await watch.until(atRest, 10_000, 'the arm at rest');
  const seen = audits.length;
  await sendTrajectory(['shoulder'], [{ positions: [0.4], time_from_start_ms: 300 }]);
  const refusal = await watch.until(
    () => audits.slice(seen).find((a) => a.kind === 'refused-command' && a.by === 'ros2'),
    10_000,
    "the controller's refusal",
  );
  expect(refusal.detail).toMatch(/alice/);
  // The arm is where it was: every later state sample equals the one before the trajectory.
  const from = watch.items.length;
  await watch.until(
    () => (watch.items.length > from + 50 ? true : undefined),
    10_000,
    'a second of states',
  );
  const after = mqttJoints()!;
  after.forEach((v, i) => expect(Math.abs(v - before[i]!) * DEG).toBeLessThan(0.01));
});
