/// <reference lib="dom" />
/**
 * Fifty arms on one page (issue 34): `armtwin up --arms arm1:armtwin5,…,arm50:armtwin5` (fifty
 * simulated arms at 50 Hz, the embedded broker) and the HUD on arm1. The page follows the other
 * arms through their summaries (docs/protocol.md § Fleets), so it stays usable: every arm is in
 * the fleet view with its state, holder and pose; an overheat on arm37 shows on its row while the
 * page shows arm1; the fleet list switches to arm37 and the twin follows it; the emergency stop
 * then goes to arm37 and stops it, and never to arm1. Frame rates are the bench's (fleet page,
 * BENCHMARKS.md), not asserted here.
 */
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { ArmObserver, until } from './support/sim.ts';
import { startUp, type UpProcess } from './support/up.ts';

const ARMS = 50;
let up: UpProcess;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(180_000);
  ensureHudBuilt();
  const list = Array.from({ length: ARMS }, (_, i) => `arm${i + 1}:armtwin5`).join(',');
  // No users file: the anonymous local demo.
  up = await startUp(testInfo.outputPath('armtwin-up-fleet.log'), ['--arms', list], '');
});

test.afterAll(async () => {
  await up?.stop();
});

test('50 arms: the fleet view, an alarm on arm37 while arm1 is shown, switching to arm37, its stop', async ({
  page,
}, testInfo) => {
  test.setTimeout(180_000);
  const arm37 = await ArmObserver.connect(up.mqttUrl, 'arm37');
  const arm1 = await ArmObserver.connect(up.mqttUrl, 'arm1');
  try {
    // Slow jog moves (6 s), so arm37 is still moving when the stop comes.
    await page.goto(`${up.url}?arm=arm1&jogms=6000`);
    await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);

    // Every arm in the fleet view, each with its state, holder and a pose from its summary.
    await expect(page.getByTestId('fleet-count')).toContainText(`${ARMS} arms · ${ARMS} online`, {
      timeout: 30_000,
    });
    await expect(page.getByTestId('fleet-state-arm37')).toHaveText('still · nobody holds it');
    await expect(page.getByTestId('fleet-pose-arm37')).toHaveAttribute(
      'data-degrees',
      /^-?\d+(\.\d)?( -?\d+(\.\d)?){5}$/,
    );
    await expect(page.getByTestId('fleet-alarm-arm37')).toHaveText('ok');

    // An overheat on arm37 shows on its row while the page shows arm1.
    await arm37.fault({ fault: 'overheat', id: 2, celsius: 150 });
    await expect(page.getByTestId('fleet-alarm-arm37')).toContainText('alarm: servo 002', {
      timeout: 30_000,
    });
    await expect(page).toHaveURL(/arm=arm1(&|$)/);
    await expect(page.getByTestId('fleet-arm1')).toHaveAttribute('aria-pressed', 'true');
    await expect(page.getByTestId('fleet-alarm-arm1')).not.toContainText('alarm');
    await shot(page, testInfo, 'fleet-50-alarm-37');
    await arm37.fault({ fault: 'clear' });

    // The fleet list switches to arm37, and the twin shows it: a move of arm37's elbow is drawn.
    await page.getByTestId('fleet-arm37').click();
    await expect(page).toHaveURL(/arm=arm37(&|$)/);
    await expect(page.getByTestId('fleet-arm37')).toHaveAttribute('aria-pressed', 'true');
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.', { timeout: 15_000 });
    const elbow = pwmFromAngle(45, 1);
    await arm37.client.publishAsync('arm/arm37/control', `#002P${elbow}T0500!`, { qos: 1 });
    await expect
      .poll(
        () => page.evaluate(() => (window as unknown as HudWindow).__armtwin!.store.rendered[2]),
        { timeout: 15_000 },
      )
      .toBeCloseTo(angleFromPwm(elbow, 1), 1);

    // The emergency stop goes to the shown arm, arm37, and stops it; arm1 gets none.
    const target = pwmFromAngle(120, 1);
    const jogAt = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('120');
    await until(() => (arm37.pwm[0] ?? 0) > 1560, 10_000, "arm37's base to start moving");
    const since = Date.now();
    await page.getByRole('button', { name: 'Emergency stop' }).click();
    await until(() => arm37.control(since).includes('#255PDST!'), 5000, '#255PDST! on arm37');
    // Judged once the 6 s jog would have ended: a stopped arm stands still, short of its target.
    await page.waitForTimeout(Math.max(0, jogAt + 6500 - Date.now()));
    const stoppedAt = arm37.pwm[0]!;
    await page.waitForTimeout(1000);
    expect(Math.abs(arm37.pwm[0]! - stoppedAt)).toBeLessThanOrEqual(1);
    expect(arm37.pwm[0]!).toBeLessThan(target - 50);
    expect(arm1.control(jogAt)).not.toContain('#255PDST!');
    await expect(page.getByTestId('fleet-state-arm37')).toContainText('still');
    await shot(page, testInfo, 'fleet-50-arm37-stopped');
  } finally {
    await arm37.close();
    await arm1.close();
  }
});
