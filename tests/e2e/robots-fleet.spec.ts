/// <reference lib="dom" />
/**
 * Robots and the fleet in the HUD, end to end (real Mosquitto, real `armtwin sim`, Debian
 * Chromium): both robots load and animate (armtwin5 from the `arm` fixture, a second sim with
 * `--profile track6`, switched to through the fleet list). The twin is read through
 * `window.__armtwin` (`joints()`: the URDF joint values as drawn).
 */
import type { Page } from '@playwright/test';
import { pwmFromServo } from '@armtwin/robot';
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { until } from './support/sim.ts';
import { loadProfile, startProfiledArm } from './support/profiled-arm.ts';
import { joints, type RobotsWindow } from './support/robots-window.ts';

const TRACK6 = loadProfile('track6');

const activeRobot = (page: Page) =>
  page.evaluate(() => {
    const a = (window as unknown as RobotsWindow).__armtwin!.robots.active;
    return { name: a.spec.name, planner: a.motion !== null, source: a.source };
  });

test('robots: armtwin5 and track6 both load and animate; the fleet list switches between them', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  const trackId = `${arm.id}-t6`;
  const track = await startProfiledArm(
    stack.broker.url,
    trackId,
    TRACK6,
    testInfo.outputPath(`sim-${trackId}.log`),
  );
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
    // Drawn as track6 from the worker's first frame of it (paced frames may come a little later).
    await expect.poll(async () => (await joints(page)).length).toBe(7);

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
