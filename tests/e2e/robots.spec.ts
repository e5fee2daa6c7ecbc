/// <reference lib="dom" />
/**
 * Robots, fleet and planning in the HUD, end to end (real Mosquitto, real `armtwin sim`, Debian Chromium): both
 * robots load and animate (armtwin5 from the `arm` fixture, a second sim with
 * `--profile track6`, switched to through the fleet list), the command box's motion requests,
 * and a Cartesian-path plan previewed on the ghost and streamed from the HUD with pose checking.
 * The twin is read through `window.__armtwin` (`joints()`: the URDF joint values as drawn).
 */
import type { Page, TestInfo } from '@playwright/test';
import { parseProfile, posePwm, pwmFromServo, type Profile } from '@armtwin/ik';
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from '../helpers/services.ts';
import { expect, shot, test, type HudWindow, type Stack } from './fixtures.ts';
import { ArmObserver, startSim, until, type SimProcess } from './support/sim.ts';

interface RobotsWindow {
  __armtwin?: {
    joints(which?: 'robot' | 'ghost'): number[];
    target: { ghostShows: string };
    robots: {
      active: { spec: { name: string }; motion: unknown; source: string };
      runner: { state: string; replans: number; pauses: number; sent: number };
      waypoints: { list: { x: number; y: number; z: number }[] };
      editor: { screenPoint(i: number): { x: number; y: number } | null } | null;
    };
  };
}

function loadProfile(name: string): Profile {
  const file = path.join(REPO_ROOT, 'public/models', name, 'profile.json');
  const r = parseProfile(JSON.parse(fs.readFileSync(file, 'utf8')));
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
}
const ARMTWIN5 = loadProfile('armtwin5');
const TRACK6 = loadProfile('track6');

const joints = (page: Page, which: 'robot' | 'ghost' = 'robot') =>
  page.evaluate((w) => (window as unknown as RobotsWindow).__armtwin!.joints(w), which);
const activeRobot = (page: Page) =>
  page.evaluate(() => {
    const a = (window as unknown as RobotsWindow).__armtwin!.robots.active;
    return { name: a.spec.name, planner: a.motion !== null, source: a.source };
  });

/** A second sim on `<id>` with `--profile <name>`, online and streaming all its servos. */
async function startArm(
  stack: Stack,
  id: string,
  profile: Profile,
  testInfo: TestInfo,
): Promise<{ sim: SimProcess; observer: ArmObserver }> {
  const observer = await ArmObserver.connect(stack.broker.url, id);
  const sim = startSim(stack.broker.url, id, testInfo.outputPath(`sim-${id}.log`), [
    '--profile',
    profile.name,
  ]);
  await until(
    () =>
      observer.online === '1' &&
      observer.pwm.filter(Number.isFinite).length === profile.servos.length,
    30_000,
    `sim ${id} (${profile.name}) online and streaming`,
  );
  return { sim, observer };
}

test('robots: armtwin5 and track6 both load and animate; the fleet list switches between them', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  const trackId = `${arm.id}-t6`;
  const track = await startArm(stack, trackId, TRACK6, testInfo);
  try {
    // armtwin5 first: announced by its sim, six sliders, the elbow jog drawn on the URDF.
    await expect
      .poll(() => activeRobot(page))
      .toEqual({
        name: 'armtwin5',
        planner: true,
        source: 'announced',
      });
    await expect(page.getByRole('slider')).toHaveCount(6);
    await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('45');
    await expect
      .poll(async () => Math.abs((await joints(page))[2]! - (45 * Math.PI) / 180), {
        timeout: 10_000,
      })
      .toBeLessThan(0.01);

    // The fleet lists both arms, online, with their robots.
    const mine = page.getByTestId(`fleet-${arm.id}`);
    const other = page.getByTestId(`fleet-${trackId}`);
    await expect(mine).toContainText('armtwin 5-axis demo arm');
    await expect(mine).toHaveAttribute('aria-pressed', 'true');
    await expect(other).toContainText('6-axis industrial arm on a linear track');
    await expect(other).toContainText('online');
    await shot(page, testInfo, 'armtwin5');

    // An overheating servo on the arm not selected shows on its badge.
    await track.observer.fault({ fault: 'overheat', id: 2, celsius: 150 });
    await expect(page.getByTestId(`fleet-alarm-${trackId}`)).toContainText(/warning|alarm/, {
      timeout: 30_000,
    });
    await track.observer.fault({ fault: 'clear' });

    // Select track6: the URL follows, 7 sliders, the track in mm, the model is track6's.
    await other.click();
    await expect(page).toHaveURL(new RegExp(`arm=${trackId}`));
    await expect
      .poll(() => activeRobot(page), { timeout: 15_000 })
      .toEqual({
        name: 'track6',
        planner: true,
        source: 'announced',
      });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    await expect(page.getByRole('slider')).toHaveCount(7);
    const trackSlider = page.getByRole('slider', { name: 'Track', exact: true });
    await expect(trackSlider).toBeEnabled();
    await expect(trackSlider).toHaveAttribute('max', '3000');
    expect((await joints(page)).length).toBe(7);

    // Jog the track to 1500 mm: the sim's carriage moves, and so does the drawn one (metres).
    const since = Date.now();
    const pwm = pwmFromServo(TRACK6.servos[0]!, 1500);
    expect(pwm).toBe(1500);
    const jogSent = () => track.observer.commands(since).includes(`#000P${pwm}T0100!`);
    await trackSlider.fill('1500');
    await until(() => jogSent(), 5000, 'the jog on the control topic');
    await until(() => track.observer.pwm[0] === pwm, 15_000, `the track at ${pwm} µs`);
    expect(jogSent()).toBe(true);
    await expect
      .poll(async () => Math.abs((await joints(page))[0]! - 1.5), { timeout: 10_000 })
      .toBeLessThan(0.005);
    // …and a revolute axis with an offset: A3 to 60° (joint), servo angle 45°.
    await page.getByRole('slider', { name: 'A3 forearm', exact: true }).fill('60');
    await expect
      .poll(async () => Math.abs((await joints(page))[3]! - (60 * Math.PI) / 180), {
        timeout: 10_000,
      })
      .toBeLessThan(0.01);
    await page.waitForTimeout(500);
    await shot(page, testInfo, 'track6');

    // And back to the 5-axis arm, at rest with its elbow at 45°. Its model is held back until
    // the page has the arm's status (a big model loads after the last report): drawn at the
    // reported pose as soon as it loads, not at zero until the arm next moves.
    let release = () => {};
    const held = new Promise<void>((resolve) => (release = resolve));
    await page.route('**/models/armtwin5/**', async (route) => {
      await held;
      await route.continue();
    });
    await mine.click();
    await expect
      .poll(() =>
        page.evaluate(() => (window as unknown as HudWindow).__armtwin!.store.rendered[2]),
      )
      .toBeCloseTo(angleFromPwm(pwmFromAngle(45, 1), 1), 1);
    release();
    await expect
      .poll(() => activeRobot(page), { timeout: 15_000 })
      .toMatchObject({
        name: 'armtwin5',
        planner: true,
      });
    await page.unroute('**/models/armtwin5/**');
    await expect
      .poll(async () => (await joints(page))[2] ?? NaN, { timeout: 3000 })
      .toBeCloseTo((45 * Math.PI) / 180, 2);
    await expect(page.getByRole('slider')).toHaveCount(6);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
  } finally {
    await track.sim.stop();
    await track.observer.close();
  }
});

test('command box: "move to 150 0 80" reaches the arm; an unreachable target says why', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const box = page.getByRole('textbox', { name: 'Command' });
  await box.fill('move to 150 0 80');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  const status = page.getByTestId('command-status').first();
  await expect(status).toHaveText('done', { timeout: 20_000 });
  await expect(status).toHaveAttribute('title', /planned.*executing.*done/);
  // The arm is there: FK of the sim's pulses, and the HUD's tip line.
  const robot = createMotionRobot(ARMTWIN5);
  const tip = tipPose(robot, arm.observer.pwm);
  expect(Math.hypot(tip.x - 150, tip.y, tip.z - 80)).toBeLessThan(2);
  await expect(page.getByTestId('tip-pose')).toHaveText(
    /Tip at x 1(49|50)\.\d, y -?0\.\d, z (79|80)\.\d mm/,
  );
  await shot(page, testInfo, 'command-done');

  await box.fill('move to 600 0 100');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  await expect(page.getByTestId('command-status').first()).toHaveText(
    /^unreachable: .+ \(code \d+\)$/,
    { timeout: 10_000 },
  );
  await box.fill('open gripper');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  await expect(page.getByTestId('command-status').first()).toHaveText('done', { timeout: 10_000 });
  const open = posePwm(ARMTWIN5, 'open')![5]!;
  expect(Math.abs(arm.observer.pwm[5]! - open)).toBeLessThanOrEqual(1);
  await box.fill('fly away');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  await expect(page.getByTestId('command-error')).toContainText('not a command');
});

/** Two waypoints by number, for a Cartesian path from home: (150, 0, 250) → (200, 0, 150). */
async function twoWaypoints(page: Page): Promise<void> {
  const add = page.getByRole('button', { name: 'Add waypoint at tip' });
  await add.click();
  await add.click();
  const set = async (n: number, x: number, y: number, z: number) => {
    await page.getByLabel(`Waypoint ${n} X`).fill(String(x));
    await page.getByLabel(`Waypoint ${n} Y`).fill(String(y));
    await page.getByLabel(`Waypoint ${n} Z`).fill(String(z));
  };
  await set(1, 150, 0, 250);
  await set(2, 200, 0, 150);
}

const runner = (page: Page) =>
  page.evaluate(() => {
    const r = (window as unknown as RobotsWindow).__armtwin!.robots.runner;
    return { state: r.state, replans: r.replans, pauses: r.pauses, sent: r.sent };
  });

test('plan: a Cartesian path through 2 waypoints previews on the ghost and executes', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  await twoWaypoints(page);

  // A sphere can be dragged in 3D: waypoint 2 moves over the floor plane, and back by number.
  await page.waitForTimeout(500); // the spheres follow the numbers on the next frame
  const at = await page.evaluate(() =>
    (window as unknown as RobotsWindow).__armtwin!.robots.editor!.screenPoint(1),
  );
  expect(at).not.toBeNull();
  await page.mouse.move(at!.x, at!.y);
  await page.mouse.down();
  await page.mouse.move(at!.x + 30, at!.y + 10, { steps: 5 });
  await page.mouse.up();
  const moved = await page.evaluate(
    () => (window as unknown as RobotsWindow).__armtwin!.robots.waypoints.list[1]!,
  );
  expect(Math.hypot(moved.x - 200, moved.y)).toBeGreaterThan(5);
  expect(moved.z).toBe(150);
  // Type over the dragged numbers once the panel shows them (typed sooner, the panel's render of
  // the drag would overwrite them), then check the plan's waypoint took them.
  await expect(page.getByLabel('Waypoint 2 X')).not.toHaveValue('200');
  await page.getByLabel('Waypoint 2 X').fill('200');
  await page.getByLabel('Waypoint 2 Y').fill('0');
  await expect
    .poll(() =>
      page.evaluate(() => {
        const w = (window as unknown as RobotsWindow).__armtwin!.robots.waypoints.list[1]!;
        return [w.x, w.y];
      }),
    )
    .toEqual([200, 0]);

  await page.getByRole('radio', { name: 'Cartesian path' }).check();
  await page.getByRole('button', { name: 'Preview', exact: true }).click();
  await expect(page.getByTestId('plan-note')).toContainText('Planned: Cartesian path');
  await expect(page.getByTestId('ghost-shows')).toContainText('previewing the plan');
  // The ghost runs along the plan: its joints change while the live arm stands still.
  const a = await joints(page, 'ghost');
  await page.waitForTimeout(700);
  const b = await joints(page, 'ghost');
  expect(Math.max(...a.map((v, i) => Math.abs(v - b[i]!)))).toBeGreaterThan(0.01);
  await shot(page, testInfo, 'plan-preview');

  const since = Date.now();
  await page.getByRole('button', { name: 'Execute', exact: true }).click();
  await expect(page.getByTestId('plan-run')).toContainText('Executing');
  await expect(page.getByTestId('plan-run')).toHaveText(/^Done/, { timeout: 20_000 });
  // The plan is over: the ghost goes (the arm is where it showed).
  await expect(page.getByTestId('ghost-shows')).toContainText('hidden');
  // Streamed as timed groups on the control topic, and the arm gets to the last waypoint. "Done"
  // comes once the last timed group is sent and the pose on the way checked; the arm's report of
  // the end of that last move arrives after it, so it is waited for, not read at once.
  const groups = arm.observer.commands(since).filter((t) => t.startsWith('{#'));
  expect(groups.length).toBeGreaterThan(10);
  expect(groups[0]).toMatch(/^\{(#\d{3}P\d{4}T0100!)+\}$/);
  const robot = createMotionRobot(ARMTWIN5);
  await expect
    .poll(() => {
      const tip = tipPose(robot, arm.observer.pwm);
      return Math.hypot(tip.x - 200, tip.y, tip.z - 150);
    })
    .toBeLessThan(3);
  expect((await runner(page)).pauses).toBe(0);
  await shot(page, testInfo, 'plan-done');
});

test('plan: pose checking pauses on a stalled servo, re-plans from the actual pose; the e-stop ends a run', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  await twoWaypoints(page);
  await page.getByRole('button', { name: 'Execute', exact: true }).click();
  await expect(page.getByTestId('plan-run')).toContainText('Executing');
  await page.waitForTimeout(400);
  await arm.observer.fault({ fault: 'stall', id: 1 });
  // The pause lasts 500 ms, then the re-plan: either may be what the panel shows when looked at.
  await expect
    .poll(async () => (await runner(page)).pauses, { timeout: 10_000 })
    .toBeGreaterThan(0);
  await expect(page.getByTestId('plan-run')).toContainText(/Paused — servo 001|re-planned/);
  await shot(page, testInfo, 'plan-paused');
  await arm.observer.fault({ fault: 'clear' });
  await expect(page.getByTestId('plan-run')).toHaveText(/^Done after \d re-plans?/, {
    timeout: 20_000,
  });
  const r = await runner(page);
  expect(r.pauses).toBeGreaterThanOrEqual(1);
  expect(r.replans).toBeGreaterThanOrEqual(1);
  const tip = tipPose(createMotionRobot(ARMTWIN5), arm.observer.pwm);
  expect(Math.hypot(tip.x - 200, tip.y, tip.z - 150)).toBeLessThan(3);

  // Back along the path, and the emergency stop (Escape) in the middle: nothing streams after it.
  await page.getByRole('button', { name: 'Delete waypoint 2' }).click();
  await page.getByRole('button', { name: 'Execute', exact: true }).click();
  await expect(page.getByTestId('plan-run')).toContainText('Executing');
  // Pressed as soon as the run has sent its first groups (a fixed wait could outlast the leg).
  await expect
    .poll(async () => {
      const r = await runner(page);
      return r.state === 'running' && r.sent > 0;
    })
    .toBe(true);
  const escapeAt = Date.now();
  await page.keyboard.press('Escape');
  await expect(page.getByTestId('plan-run')).toHaveText('Stopped: emergency stop.');
  await page.waitForTimeout(800);
  // Judged by order on the control topic, not by clocks: after the `#255PDST!` no group follows
  // (a group sent just before the stop may still be arriving when the panel says "Stopped").
  const after = arm.observer.commands(escapeAt - 1000);
  const stopIndex = after.indexOf('#255PDST!');
  expect(stopIndex).toBeGreaterThanOrEqual(0);
  expect(after.slice(stopIndex + 1).filter((t) => t.startsWith('{#'))).toEqual([]);
});
