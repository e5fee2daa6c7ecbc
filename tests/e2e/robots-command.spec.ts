/**
 * The command box's motion requests, end to end (real Mosquitto, real `armtwin sim`, Debian
 * Chromium): a reachable target reaches the arm, an unreachable one says why.
 */
import { posePwm } from '@armtwin/robot';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { expect, shot, test } from './fixtures.ts';
import { loadProfile } from './support/profiled-arm.ts';

const ARMTWIN5 = loadProfile('armtwin5');

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
