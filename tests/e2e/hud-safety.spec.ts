/// <reference lib="dom" />
/**
 * The HUD end to end, safety: an injected overheat turns the servo critical, the emergency stop
 * (button and Escape) halts the simulator, a dead simulator shows "offline" and disables
 * jogging. Real Mosquitto (WebSockets), the real simulator (`armtwin sim`, observed with an
 * mqtt.js subscriber), the built HUD in Debian Chromium.
 */
import { pwmFromAngle } from '@armtwin/protocol';
import { expect, shot, test } from './fixtures.ts';
import { until } from './support/sim.ts';

test('health: an injected overheat turns that servo critical', async ({ hud, arm }, testInfo) => {
  const { page } = hud;
  await expect(page.getByTestId('health-2')).toHaveClass(/temp-normal/);
  await arm.observer.fault({ fault: 'overheat', id: 2, celsius: 150 });
  await expect(page.getByTestId('health-2')).toHaveClass(/temp-critical/, { timeout: 30_000 });
  await expect(page.getByRole('alert').filter({ hasText: 'Overheating' })).toContainText('Elbow');
  await expect(page.getByRole('alert').filter({ hasText: 'Overheating' })).toContainText(
    'Cut the power',
  );
  await expect(page.getByTestId('health-announcer')).toContainText('Elbow: temperature');
  await expect(page.getByTestId('health-announcer')).toContainText(
    'critical, overheating — cut the power',
  );
  await expect(page.getByTestId('health-1')).not.toHaveClass(/temp-critical/);
  await shot(page, testInfo, 'overheat');
});

test.describe('emergency stop', () => {
  // Slow jog moves (6 s), so the arm is still moving when the stop comes.
  test.use({ hudQuery: '&jogms=6000' });

  test('the button and Escape publish #255PDST! at QoS 1 and halt the simulator', async ({
    hud,
    arm,
  }, testInfo) => {
    const { page } = hud;
    const target = pwmFromAngle(120, 1);
    const jogAt = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('120');
    await until(() => (arm.observer.pwm[0] ?? 0) > 1560, 10_000, 'the base to start moving');
    const since = Date.now();
    await page.getByRole('button', { name: 'Emergency stop' }).click();
    await until(
      () => arm.observer.control(since).includes('#255PDST!'),
      5000,
      '#255PDST! on the control topic',
    );
    expect(arm.observer.controlMessages(since).find((m) => m.text === '#255PDST!')?.qos).toBe(1);
    // Judged once the 6 s jog would have ended, so a late status report cannot pass for a stop:
    // an arm that was not stopped is at the target by then; a stopped one stands still, short.
    await page.waitForTimeout(Math.max(0, jogAt + 6500 - Date.now()));
    const stoppedAt = arm.observer.pwm[0]!;
    await page.waitForTimeout(1000);
    expect(Math.abs(arm.observer.pwm[0]! - stoppedAt)).toBeLessThanOrEqual(1);
    expect(arm.observer.pwm[0]!).toBeLessThan(target - 50);
    await shot(page, testInfo, 'estop');

    const again = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).focus();
    await page.keyboard.press('Escape');
    await until(
      () => arm.observer.control(again).includes('#255PDST!'),
      5000,
      '#255PDST! after Escape',
    );
  });
});

test('offline: killing the simulator shows "offline" and disables jogging', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  await expect(page.getByTestId('arm-online')).toHaveText('online');
  await arm.sim.kill();
  await expect(page.getByTestId('arm-online')).toHaveText('offline', { timeout: 15_000 });
  await expect(page.getByTestId('freshness')).toContainText('Data is stale');
  await expect(page.getByRole('slider', { name: 'Base', exact: true })).toBeDisabled();
  await shot(page, testInfo, 'offline');
});
