/// <reference lib="dom" />
/**
 * Planning in the HUD, end to end (real Mosquitto, real `armtwin sim`, Debian Chromium): a
 * Cartesian-path plan previewed on the ghost and streamed from the HUD with pose checking, which
 * pauses on a stalled servo and re-plans; the e-stop ends a run. The twin is read through
 * `window.__armtwin` (`joints()`: the URDF joint values as drawn).
 */
import type { Page } from '@playwright/test';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { expect, shot, test } from './fixtures.ts';
import { loadProfile } from './support/profiled-arm.ts';
import { addWaypoints, joints, runner, type RobotsWindow } from './support/robots-window.ts';

const ARMTWIN5 = loadProfile('armtwin5');

/** Two waypoints by number, for a Cartesian path from home: (150, 0, 250) → (200, 0, 150). */
const twoWaypoints = (page: Page) =>
  addWaypoints(page, [
    { x: 150, y: 0, z: 250 },
    { x: 200, y: 0, z: 150 },
  ]);

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
