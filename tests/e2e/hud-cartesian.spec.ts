/// <reference lib="dom" />
/**
 * The HUD end to end, Cartesian targets: below the floor refused with the reason, the target
 * starting at the tip, an unreachable target publishing nothing, a reachable one reaching the
 * arm. Real Mosquitto (WebSockets), the real simulator (`armtwin sim`, observed with an mqtt.js
 * subscriber), the built HUD in Debian Chromium.
 */
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { forwardKinematics, jointsFromServoAngles, solveIk, type Quad } from '@armtwin/ik';
import { expect, renderedAngles, shot, test } from './fixtures.ts';
import { until } from './support/sim.ts';

test('floor: a target or jog below the floor is refused in the page, with the reason', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const since = Date.now();
  // Command box: reachable by the IK, but the hand would end 11 mm under the floor.
  const box = page.getByRole('textbox', { name: 'Command' });
  await box.fill('move to 200 0 -50');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  await expect(page.getByTestId('command-error')).toHaveText(
    /^Not sent: tip \d+\.\d mm below the floor \(z -\d+\.\d < 0\)\.$/,
  );
  await expect(page.getByTestId('command-entry')).toHaveCount(0);
  // Cartesian panel: the preview says so, and Move sends nothing.
  await page.getByLabel('X', { exact: true }).fill('200');
  await page.getByLabel('Y', { exact: true }).fill('0');
  await page.getByLabel('Z', { exact: true }).fill('-50');
  await expect(page.getByTestId('ik-preview')).toHaveText(
    /^Unreachable: tip \d+\.\d mm below the floor \(z -\d+\.\d < 0\) \(code 24\)\.$/,
  );
  await page.getByRole('button', { name: 'Move' }).click();
  await expect(page.getByTestId('kms-refusal')).toContainText('below the floor');
  // Jog: upper arm level is fine (hand at z 100); the forearm down from there is not.
  await page.getByRole('slider', { name: 'Shoulder', exact: true }).fill('-90');
  const level = pwmFromAngle(-90, 1);
  await until(() => arm.observer.pwm[1] === level, 10_000, `the sim's shoulder at ${level} µs`);
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('-90');
  await expect(page.getByTestId('jog-refusal')).toHaveText(
    /^Not sent: tip \d+\.\d mm below the floor/,
  );
  await page.waitForTimeout(1000);
  expect(arm.observer.pwm[2]).toBe(1500);
  expect(arm.observer.commands(since)).toEqual([`#001P${String(level).padStart(4, '0')}T0100!`]);
  await shot(page, testInfo, 'floor-refused');
});

test('cartesian: the target starts at the tip of the arm, which it reaches', async ({ hud }) => {
  const { page } = hud;
  // armtwin5 at home points straight up: its tip is at (0, 0, 453).
  await expect(page.getByLabel('X', { exact: true })).toHaveValue('0');
  await expect(page.getByLabel('Y', { exact: true })).toHaveValue('0');
  await expect(page.getByLabel('Z', { exact: true })).toHaveValue('453');
  // Retyped as it stands (a value put back unchanged is not an edit), the target is reachable.
  await page.getByLabel('Z', { exact: true }).fill('');
  await page.getByLabel('Z', { exact: true }).fill('453');
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
});

test('cartesian: an unreachable target shows the reason and publishes nothing', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const before = [...arm.observer.pwm];
  const since = Date.now();
  await page.getByLabel('X', { exact: true }).fill('600');
  await page.getByLabel('Y', { exact: true }).fill('0');
  await page.getByLabel('Z', { exact: true }).fill('100');
  await expect(page.getByTestId('ik-preview')).toHaveText('Unreachable: out of reach (code 2).');
  await page.getByRole('button', { name: 'Move' }).click();
  await expect(page.getByTestId('kms-refusal')).toHaveText('Not sent: out of reach (code 2).');
  await page.keyboard.press('Enter'); // submitting the form again does not send either
  await page.waitForTimeout(1500);
  // Only the HUD's $PNG round-trip pings may appear on the control topic.
  expect(arm.observer.commands(since)).toEqual([]);
  expect(arm.observer.pwm).toEqual(before);
  await shot(page, testInfo, 'unreachable');
});

test('cartesian: a reachable target reaches the arm', async ({ hud, arm }, testInfo) => {
  const { page } = hud;
  const [x, y, z] = [180, 100, 80];
  const ik = solveIk(x, y, z);
  expect(ik.code).toBe(0);
  const since = Date.now();
  await page.getByLabel('X', { exact: true }).fill(String(x));
  await page.getByLabel('Y', { exact: true }).fill(String(y));
  await page.getByLabel('Z', { exact: true }).fill(String(z));
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
  await expect(page.getByTestId('ghost-shows')).toContainText('previewed target pose');
  await shot(page, testInfo, 'reachable-preview');
  await page.getByRole('button', { name: 'Move' }).click();
  await until(
    () => arm.observer.commands(since).includes(`$KMS:${x},${y},${z},1500!`),
    5000,
    'the $KMS command',
  );
  await expect(page.getByTestId('kms-reply')).toContainText('code 0 — accepted, moving');
  await until(
    () => ik.pwm.every((p, i) => Math.abs((arm.observer.pwm[i] ?? 0) - p) <= 1),
    10_000,
    `the sim at ${ik.pwm.join(', ')} µs`,
  );
  const s = arm.observer.pwm.slice(0, 4).map((p) => angleFromPwm(p, 1)) as Quad;
  const tip = forwardKinematics(jointsFromServoAngles(s));
  expect(Math.hypot(tip.x - x, tip.y - y, tip.z - z)).toBeLessThan(2);
  await expect
    .poll(
      async () => {
        const r = await renderedAngles(page);
        return Math.max(...ik.servoAngles.map((a, i) => Math.abs(r[i]! - a)));
      },
      { timeout: 5000 },
    )
    .toBeLessThan(0.5);
  await shot(page, testInfo, 'reachable-arrived');
});
