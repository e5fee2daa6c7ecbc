/// <reference lib="dom" />
/**
 * The predictive twin and the tracking-error paint, end to end (issue 17 items 1 and 4; real
 * Mosquitto, a real `armtwin sim`, Chromium). Another client moves the shoulder slowly on the
 * arm's control topic (the page reads everyone's commands there), then the simulator's fault
 * injection jams it (`{"fault":"stall"}`): the twin, drawn ahead of the reports while the arm
 * moves and saying so ("Predicted"), comes back to the jammed joint's reported angle; the
 * shoulder's link is painted in the error colour and its legend entry shows the error.
 * No timings are asserted: each step waits for what a user would see.
 */
import { angleFromPwm } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';
import type { Page } from '@playwright/test';
import { expect, shot, test } from './fixtures.ts';
import { holdsStill, movedFrom } from './support/arm-motion.ts';
import type { ArmObserver } from './support/sim.ts';

const SHOULDER = 1;
const BASE = 0;

interface TwinWindow {
  __armtwin: {
    store: {
      rendered: Float64Array;
      angle: Float64Array;
      predicting: boolean;
      tracking: { levels: string[]; errorDeg: Float64Array };
    };
    viewer: { tracking: { levels: string[] } | null };
  };
}

const drawn = (page: Page, i: number) =>
  page.evaluate((k) => (window as unknown as TwinWindow).__armtwin.store.rendered[k]!, i);

/** Servo i's angle as the arm last reported it to the test's own subscriber, degrees. */
const reported = (o: ArmObserver, i: number) =>
  angleFromPwm(o.pwm[i]!, DEMO_ARM.servos[i]!.polarity);

/** Starts a slow shoulder move (54° over 6 s) and a base move, as another client would. */
async function moveSlowly(o: ArmObserver): Promise<void> {
  await o.client.publishAsync(`arm/${o.armId}/control`, '{#000P1700T4000!#001P1900T6000!}', {
    qos: 1,
  });
  await movedFrom(o, SHOULDER, 1500, 20);
}

test.describe('predictive twin', () => {
  test('draws the moving arm ahead of its reports, says so, and follows a stall back to the reports', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    const o = arm.observer;
    const note = page.getByTestId('twin-prediction');
    await expect(note).toHaveText('Drawn as the arm reports.');
    await moveSlowly(o);
    // While the shoulder moves, what is drawn is a prediction, and the page says so.
    await expect(note).toHaveAttribute('data-predicting', 'true');
    await expect(note).toContainText(/Predicted: drawn \d+ ms ahead of the arm's last report/);
    await shot(page, testInfo, 'twin-predicting');

    await o.fault({ fault: 'stall', id: SHOULDER });
    expect(await holdsStill(o, SHOULDER)).toBe(true);
    // Jammed: the twin shows the shoulder where the arm reports it, not where it was heading.
    const jammedAt = reported(o, SHOULDER);
    await expect
      .poll(async () => Math.abs((await drawn(page, SHOULDER)) - jammedAt), {
        message: 'the drawn shoulder back on the reported (jammed) angle',
      })
      .toBeLessThan(0.2);
    // And it stays there (the command's course no longer drives it).
    expect(await holdsStill(o, SHOULDER)).toBe(true);
    expect(Math.abs((await drawn(page, SHOULDER)) - reported(o, SHOULDER))).toBeLessThan(0.2);
    // Once the base has arrived too, nothing is predicted any more.
    await expect(note).toHaveAttribute('data-predicting', 'false', { timeout: 15_000 });
    await expect(note).toHaveText('Drawn as the arm reports.');
    await shot(page, testInfo, 'twin-stalled');
  });
});

test.describe('tracking error paint', () => {
  test('paints the stalled joint’s link in the error colour and lists its error', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    const o = arm.observer;
    const shoulder = page.getByTestId(`tracking-${SHOULDER}`);
    const base = page.getByTestId(`tracking-${BASE}`);
    const toggle = page.getByRole('checkbox', { name: 'Paint tracking error on the arm' });
    // Nothing commanded yet: the paint is off by default.
    await expect(toggle).not.toBeChecked();
    await moveSlowly(o);
    await expect(toggle).toBeChecked();
    // Moving as commanded: tracking.
    await expect(shoulder).toHaveAttribute('data-level', 'ok');
    await expect(base).toHaveAttribute('data-level', 'ok');

    await o.fault({ fault: 'stall', id: SHOULDER });
    await expect(shoulder).toHaveAttribute('data-level', 'error', { timeout: 15_000 });
    await expect(shoulder).toContainText(/\d+\.\d° \(off its command\)/);
    await expect(base).not.toHaveAttribute('data-level', 'error');
    // The link in the 3D view is painted at that level.
    const linkLevels = () =>
      page.evaluate(() => (window as unknown as TwinWindow).__armtwin.viewer.tracking?.levels);
    await expect.poll(async () => (await linkLevels())?.[SHOULDER]).toBe('error');
    await shot(page, testInfo, 'tracking-stalled');

    // Switched off, nothing is painted.
    await toggle.uncheck();
    await expect.poll(async () => (await linkLevels())?.[SHOULDER]).toBe('none');
    await expect(shoulder).toHaveCount(0);
  });
});
