/// <reference lib="dom" />
/**
 * A bus servo that turns further than its URDF says is drawn where the arm reports it: armtwin5
 * with its wrist roll (004) a ±360° angle servo (PROTOCOL.md §8) in the profile, while the URDF
 * keeps ±135°. The twin shows what the arm reports; limits are the controller's business, so
 * urdf-loader must not clamp the drawn joint to the URDF's range. `armtwin up --models DIR`
 * simulates the arm and serves the folder; an operator's MQTT client sends the move.
 */
import type { Page } from '@playwright/test';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { ArmWatcher, demoPassword, startUpWithProfile, type UpProcess } from './support/up.ts';

const PROFILE = 'wide5';
let up: UpProcess;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  up = await startUpWithProfile(PROFILE, testInfo.project.outputDir, (profile) => {
    const servos = [...profile.servos];
    servos[4] = { ...servos[4], units: 'angle', min: -360, max: 360 };
    return { ...profile, servos };
  });
});

test.afterAll(async () => {
  await up?.stop();
});

/** The URDF joint values the live arm is drawn with, rad. */
const drawnJoints = (page: Page) =>
  page.evaluate(() =>
    (window as unknown as { __armtwin: { joints(): number[] } }).__armtwin.joints(),
  );

test('a ±360° bus joint at +350° is drawn at +350°, past its URDF limit of 135°', async ({
  page,
}, testInfo) => {
  await page.goto(`${up.url}?arm=arm1`);
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill('viewer');
  await form.getByLabel('Password').fill(demoPassword('viewer'));
  await form.getByRole('button', { name: 'Log in' }).click();
  await expect
    .poll(() =>
      page.evaluate(
        () =>
          (window as unknown as { __armtwin: { robots: { active: { spec: { name: string } } } } })
            .__armtwin.robots.active.spec.name,
      ),
    )
    .toBe(PROFILE);

  const operator = await ArmWatcher.connect(up.mqttUrl, 'arm1', 'operator');
  try {
    // An operator's own control topic (docs/protocol.md § Control): the plain one is not theirs.
    await operator.client.publishAsync('arm/arm1/control/operator', '#004A+350.00T0800!', {
      qos: 1,
    });
    // URDF joint values in rad: the wrist roll's (servo 004) reaches 350° and is not held at 135°.
    await expect
      .poll(async () => ((await drawnJoints(page))[4]! * 180) / Math.PI, { timeout: 15_000 })
      .toBeCloseTo(350, 1);
    await shot(page, testInfo, 'wrist-roll-350');
  } finally {
    await operator.close();
  }
});
