/// <reference lib="dom" />
/**
 * The HUD twins a ROS 2 arm, end to end. UFACTORY's xArm7 description as PyPI's
 * example-robot-data ships it (xacro output with `<ros2_control>` and `<transmission>` blocks) is
 * imported with `armtwin robot import` into a models folder that `armtwin up` (with log-ins)
 * serves, meshes included. The ROS 2 test node (python/armtwin_ros2/test_arm.py, on real rclpy
 * and FastDDS) plays the arm's joint_trajectory_controller and joint_state_broadcaster;
 * `armtwin gateway --ros2` makes it armtwin's arm2. The page draws the xArm7 with every mesh,
 * posed by the node's joint states; when another ROS 2 node sends the controller a trajectory the
 * page shows the arm moving there; an operator's jog in the HUD moves the ROS 2 arm, as a ROS 2
 * subscriber to /joint_states sees it, and the page shows it there.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import type { Ros2Bridge } from '@armtwin/ros2';
import { REPO_ROOT } from '../helpers/services.ts';
import { exampleRobotDataDir, ROS2_ROBOTS } from '../helpers/rtb-data.ts';
import { startRos2Side, startTestArm, testDomain } from '../helpers/ros2.ts';
import { armtwin, type Child } from '../integration/sim-helpers.ts';
import { expect, shot, test } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUp, type UpProcess } from './support/up.ts';

interface Ros2HudWindow {
  __armtwin?: {
    ready?: boolean;
    joints(which?: 'robot' | 'ghost'): number[];
    robots: { active: { spec: { name: string } } };
    viewer: {
      meshFailures: readonly { url: string; message: string }[];
      drawnWorld: { traverse(fn: (o: { isMesh?: boolean }) => void): void };
    };
  };
}

const ARM = 'arm2'; // the sample users file's second device
const JOINTS = ['joint1', 'joint2', 'joint3', 'joint4', 'joint5', 'joint6', 'joint7'];
/** Where the node's arm starts, rad (joint4 inside its 0…225° range). */
const INITIAL = [0.3, -0.2, 0.1, 0.9, 0, 0.4, -0.3];
const DEG = Math.PI / 180;
const TRAJECTORY = '/joint_trajectory_controller/joint_trajectory';
const domain = testDomain();

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-ros2-'));
let up: UpProcess;
let rosArm: Awaited<ReturnType<typeof startTestArm>> | undefined;
let ros: Ros2Bridge | undefined;
let gateway: Child | undefined;
/** The node's latest joint positions (rad) by name, as a ROS 2 subscriber sees them. */
const rosJoints = new Map<string, number>();

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(180_000);
  ensureHudBuilt();
  execFileSync(
    process.execPath,
    [
      ...[path.join(REPO_ROOT, 'apps/cli/bin/armtwin.mjs'), 'robot', 'import'],
      ...[path.join(exampleRobotDataDir(), ROS2_ROBOTS.xarm7), '--name', 'xarm7'],
      ...['--models', dir],
    ],
    { cwd: REPO_ROOT, stdio: 'pipe' },
  );
  up = await startUp(path.join(testInfo.project.outputDir, `armtwin-up-ros2-${process.pid}.log`), [
    '--models',
    dir,
  ]);
  rosArm = await startTestArm([
    ...['--joints', JOINTS.join(','), '--initial', INITIAL.join(',')],
    ...['--domain', String(domain), '--rate', '50', '--trajectory', TRAJECTORY],
  ]);
  ros = await startRos2Side(domain);
  await ros.subscribe('/joint_states', 'joint_state', (m) =>
    m.name.forEach((n, i) => rosJoints.set(n, m.position[i]!)),
  );
  await ros.advertise(TRAJECTORY, 'joint_trajectory', { waitMs: 10_000 });
  gateway = armtwin(
    [
      ...['gateway', '--ros2', '--domain', String(domain), '--trajectory', TRAJECTORY],
      ...['--profile', 'xarm7', '--models', dir, '--mqtt', up.mqttUrl, '--arm', ARM],
      // only a `0` (a page let go) holds the arm: a beat late under load would stop a jog
      // half-way; the deadman's lease has its own test (deadman.spec.ts)
      ...['--operator-lease', '0'],
    ],
    { MQTT_USERNAME: ARM, MQTT_PASSWORD: demoPassword(ARM) },
  );
});

// eslint-disable-next-line no-empty-pattern
test.afterAll(async ({}, testInfo) => {
  await gateway?.stop();
  if (gateway)
    fs.writeFileSync(
      path.join(testInfo.project.outputDir, `gateway-ros2-${process.pid}.log`),
      gateway.output(),
    );
  await ros?.close();
  await rosArm?.stop();
  await up?.stop();
  fs.rmSync(dir, { recursive: true, force: true });
});

async function open(page: Page) {
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  // render=main: the live arm's meshes (counted below) are on the page only then; a long
  // keep-alive for the reason in calibration.spec.ts.
  await page.goto(`${up.url}?arm=${ARM}&render=main&keepalive=60`);
  await page.waitForFunction(() => (window as unknown as Ros2HudWindow).__armtwin?.ready === true);
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill('operator');
  await form.getByLabel('Password').fill(demoPassword('operator'));
  await form.getByRole('button', { name: 'Log in' }).click();
  await expect
    .poll(
      () =>
        page.evaluate(
          () => (window as unknown as Ros2HudWindow).__armtwin!.robots.active.spec.name,
        ),
      { timeout: 30_000 },
    )
    .toBe('xarm7');
}

/** The live twin's joint `i`, degrees. */
const drawn = (page: Page, i: number) =>
  page
    .evaluate((k) => (window as unknown as Ros2HudWindow).__armtwin!.joints()[k]!, i)
    .then((rad) => rad / DEG);
/** The ROS 2 arm's joint `name`, degrees, from its latest joint state. */
const inRos = (name: string) => (rosJoints.get(name) ?? NaN) / DEG;

test('the twin is the imported xArm7, drawn with every mesh, posed and moved by the node’s joint states', async ({
  page,
}, testInfo) => {
  await open(page);
  const meshes = await page.evaluate(() => {
    const v = (window as unknown as Ros2HudWindow).__armtwin!.viewer;
    let n = 0;
    v.drawnWorld.traverse((o) => {
      if (o.isMesh) n++;
    });
    return { n, failures: v.meshFailures.map((f) => `${f.url}: ${f.message}`) };
  });
  expect(meshes.failures).toEqual([]);
  expect(meshes.n).toBeGreaterThanOrEqual(JOINTS.length + 1); // base + one per moving link
  await expect(page.getByTestId('mesh-failures')).toBeHidden();
  for (const [i, q] of INITIAL.entries())
    await expect.poll(() => drawn(page, i), { timeout: 20_000 }).toBeCloseTo(q / DEG, 1);

  // Another ROS 2 node (MoveIt, a teleop) drives the controller: the page follows the arm.
  ros!.publish(TRAJECTORY, 'joint_trajectory', {
    joint_names: ['joint1', 'joint3'],
    points: [{ positions: [-0.6, 0.8], time_from_start_ms: 1500 }],
  });
  await expect.poll(() => inRos('joint1'), { timeout: 15_000 }).toBeCloseTo(-0.6 / DEG, 1);
  await expect.poll(() => drawn(page, 0), { timeout: 15_000 }).toBeCloseTo(-0.6 / DEG, 1);
  await expect.poll(() => drawn(page, 2), { timeout: 15_000 }).toBeCloseTo(0.8 / DEG, 1);
  await shot(page, testInfo, 'ros2-xarm7');
});

test('an operator’s jog in the HUD moves the ROS 2 arm, and the page shows it there', async ({
  page,
}, testInfo) => {
  await open(page);
  const slider = page.getByRole('slider', { name: 'joint2', exact: true });
  await expect(slider).toBeEnabled();
  const others = JOINTS.filter((j) => j !== 'joint2').map(inRos);
  await slider.fill('30');
  // joint2 is a pulse servo: 30° goes out as the nearest pulse, 1722 µs = 29.97°
  await expect.poll(() => inRos('joint2'), { timeout: 20_000 }).toBeCloseTo(30, 0);
  expect(Math.abs(inRos('joint2') - 30)).toBeLessThan(0.1);
  await expect.poll(() => drawn(page, 1), { timeout: 15_000 }).toBeCloseTo(inRos('joint2'), 1);
  // the rest of the arm stays where it was
  const after = JOINTS.filter((j) => j !== 'joint2').map(inRos);
  others.forEach((deg, k) => expect(after[k]).toBeCloseTo(deg, 3));
  await shot(page, testInfo, 'ros2-xarm7-jogged');
});
