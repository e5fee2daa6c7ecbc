/**
 * `armtwin up --ros2`: the whole twin with its simulated arms shown in ROS 2 (real rclpy and
 * FastDDS): a ROS 2 node sees each arm's joint states under its own namespace, with the URDF
 * joint names of that arm's profile.
 */
import { afterAll, beforeAll, expect, test } from 'vitest';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import type { JointStateMsg, Ros2Bridge } from '@armtwin/ros2';
import { freePorts } from '../helpers/services.ts';
import { startRos2Side, testDomain } from '../helpers/ros2.ts';
import { ARMTWIN, startUpProcess, type Child } from './sim-helpers.ts';

const domain = testDomain();
const joints = (profile: string) => readRobotFolder(profile).profile.servos.map((s) => s.joint);
let up: Child;
let ros: Ros2Bridge;
const seen = new Map<string, JointStateMsg>();

beforeAll(async () => {
  ros = await startRos2Side(domain);
  for (const arm of ['arm_a', 'arm_b'])
    await ros.subscribe(`/armtwin/${arm}/joint_states`, 'joint_state', (m) => seen.set(arm, m));
  const [httpPort = 0, mqttPort = 0] = await freePorts(2);
  process.env.ROS_DOMAIN_ID = String(domain); // inherited by `armtwin up` and its bridges
  up = await startUpProcess(
    [ARMTWIN, 'up'],
    ['--ros2', '--no-middleware', '--no-web', '--arms', 'arm-a:armtwin5,arm-b:track6'],
    { httpPort, mqttPort },
  );
});

afterAll(async () => {
  delete process.env.ROS_DOMAIN_ID;
  await up?.stop();
  await ros?.close();
});

test('each simulated arm publishes its joint states in ROS 2 under /armtwin/<arm>', async () => {
  const deadline = Date.now() + 30_000;
  while (seen.size < 2 && Date.now() < deadline) await new Promise((r) => setTimeout(r, 200));
  expect(seen.get('arm_a')?.name).toEqual(joints('armtwin5'));
  expect(seen.get('arm_b')?.name).toEqual(joints('track6'));
  expect(up.output()).toMatch(/ros2: arm-b in ROS 2 \(domain \d+\)/);
});
