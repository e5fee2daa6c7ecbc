/// <reference lib="dom" />
/**
 * Hold-to-jog end to end (issue 18; real Mosquitto, a real `armtwin sim`, Chromium): a joint
 * moves only while its − / + button (mouse or finger) or its hold key is held, and stops when it
 * is let go, when the window loses focus, and when the page stalls (the keep-alives stop, and the
 * arm stops at the end of the last short move by itself); the tip moves along z through the IK.
 * What the arm does is read by a raw MQTT subscriber.
 */
import fs from 'node:fs';
import path from 'node:path';
import { solveIk } from '@armtwin/ik';
import { parseProfile } from '@armtwin/robot';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { REPO_ROOT } from '../helpers/services.ts';
import { expect, shot, test } from './fixtures.ts';
import { holdsStill, movedFrom, movesOf, nextPulses } from './support/arm-motion.ts';
import { until } from './support/sim.ts';

const BASE = 0;

/** The demo arm's planner model, for the tip's height from the reported pulses. */
const parsed = parseProfile(
  JSON.parse(
    fs.readFileSync(path.join(REPO_ROOT, 'public', 'models', 'armtwin5', 'profile.json'), 'utf8'),
  ),
);
if (!parsed.ok) throw new Error('armtwin5 profile does not parse');
const arm5 = createMotionRobot(parsed.profile);

test.describe('hold-to-jog', () => {
  test('the + button moves the base only while held, at the chosen speed', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    const o = arm.observer;
    await page.getByTestId('hold-speed').selectOption('30');
    const plus = page.getByRole('button', { name: 'Hold Base +' });
    await expect(plus).toBeVisible();
    const box = (await plus.boundingBox())!;
    expect(Math.min(box.width, box.height), 'a finger-sized target').toBeGreaterThanOrEqual(44);

    const start = o.pwm[BASE]!;
    const pressedAt = Date.now();
    await plus.hover();
    await page.mouse.down();
    const a = await movedFrom(o, BASE, start);
    const b = await movedFrom(o, BASE, a); // still going while held
    expect(b).toBeGreaterThan(a);
    await expect(page.getByTestId('hold-state')).toHaveText('moving: Base');
    // keep-alives: short moves in 250 ms
    expect(movesOf(o, BASE, pressedAt).every((t) => /#000P\d{4}T0250!/.test(t))).toBe(true);
    await shot(page, testInfo, 'hold-jog-held');

    const releasedAt = Date.now();
    await page.mouse.up();
    await until(() => o.commands(releasedAt).includes('#000PDST!'), 5000, 'the stop on release');
    expect(await holdsStill(o, BASE)).toBe(true);
    const stoppedAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stoppedAt)).toEqual([]);
    await expect(page.getByTestId('hold-state')).toHaveText('hold − / + to move');
  });

  test('a finger on − moves the base while it touches, and stops when lifted', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    const cdp = await page.context().newCDPSession(page);
    await cdp.send('Emulation.setTouchEmulationEnabled', { enabled: true, maxTouchPoints: 1 });
    const b = (await page.getByRole('button', { name: 'Hold Base −' }).boundingBox())!;
    const point = { x: b.x + b.width / 2, y: b.y + b.height / 2 };
    const start = o.pwm[BASE]!;
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [point] });
    const a = await movedFrom(o, BASE, start);
    expect(a).toBeLessThan(start);
    await movedFrom(o, BASE, a);
    const liftedAt = Date.now();
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
    await until(() => o.commands(liftedAt).includes('#000PDST!'), 5000, 'the stop on lift');
    expect(await holdsStill(o, BASE)).toBe(true);
    const stillAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stillAt)).toEqual([]);
  });

  test('a hold key moves its joint while held; the window losing focus stops it', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    await expect(page.getByTestId('hold-keys')).toContainText('Base: A − / Q +');
    const start = o.pwm[BASE]!;
    await page.locator('body').click({ position: { x: 5, y: 5 } });
    await page.keyboard.down('a');
    const a = await movedFrom(o, BASE, start);
    expect(a).toBeLessThan(start); // A is −
    await movedFrom(o, BASE, a);

    // Focus leaves the page with the key still down: the page lets go at once.
    const blurredAt = Date.now();
    await page.evaluate(() => window.dispatchEvent(new Event('blur')));
    await until(() => o.commands(blurredAt).includes('#000PDST!'), 5000, 'the stop on blur');
    expect(await holdsStill(o, BASE)).toBe(true);
    const stillAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stillAt), 'no keep-alive after blur').toEqual([]);
    await page.keyboard.up('a');

    // Pressed again, it moves again; released, it stops.
    const again = o.pwm[BASE]!;
    await page.keyboard.down('q');
    await movedFrom(o, BASE, again);
    const upAt = Date.now();
    await page.keyboard.up('q');
    await until(() => o.commands(upAt).includes('#000PDST!'), 5000, 'the stop on key up');
    expect(await holdsStill(o, BASE)).toBe(true);
  });

  test('a page that stalls mid-jog leaves the arm stopped (keep-alives stop)', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    await page.getByTestId('hold-speed').selectOption('30');
    const start = o.pwm[BASE]!;
    await page.locator('body').click({ position: { x: 5, y: 5 } });
    await page.keyboard.down('q');
    await movedFrom(o, BASE, await movedFrom(o, BASE, start));

    // The page's main thread stalls for 2 s (under the deadman's 2.5 s lease) with Q held down.
    const stallStart = Date.now();
    const stall = page.evaluate(() => {
      const end = performance.now() + 2000;
      while (performance.now() < end);
    });
    // Well inside the stall (after the last short move's 250 ms), the arm has stopped by itself
    // and holds still.
    await nextPulses(o, BASE, 15);
    const still = await holdsStill(o, BASE);
    const checkedBy = Date.now();
    await stall;
    expect(checkedBy - stallStart, 'checked while the page was still stalled').toBeLessThan(2000);
    expect(still).toBe(true);
    const during = o.controlMessages(stallStart + 200).filter((m) => m.at <= checkedBy);
    expect(during.map((m) => m.text).filter((t) => t.startsWith('#000P'))).toEqual([]);
    await page.keyboard.up('q');
    // The stop comes on key up, or before it: the first keep-alive tick after the stall may find
    // the arm's data stale and end the hold itself ("Stopped: … data is stale"). Nothing of the
    // page's went out during the stall, so every stop since it began came after it.
    await until(
      () => o.commands(stallStart).includes('#000PDST!'),
      5000,
      'the stop after the stall',
    );
    expect(await holdsStill(o, BASE)).toBe(true);
  });

  test('the tip goes up while "tip z +" is held, through the IK; at the top it stops and says why', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    const tipZ = () => tipPose(arm5, o.pwm.slice(0, 6)).z;
    // At home the arm points straight up: the tip can go no higher, nothing is sent.
    await page.getByTestId('tip-hold').locator('summary').click();
    const z = page.getByRole('button', { name: 'Hold tip z +' });
    const since = Date.now();
    await z.hover();
    await page.mouse.down();
    await expect(page.getByTestId('hold-refusal')).toContainText('Stopped:');
    await page.mouse.up();
    expect(o.commands(since).filter((t) => /#00\dP\d{4}T/.test(t))).toEqual([]);

    // Bent (a pose of the IK's, tip at (250, 0, 200) level), the tip rises while held.
    const pose = solveIk(250, 0, 200, 0, arm5.arm!).pwm.slice(0, 4);
    await o.client.publishAsync(
      `arm/${arm.id}/control`,
      `{${pose.map((p, i) => `#00${i}P${Math.round(p)}T0300!`).join('')}}`,
      { qos: 1 },
    );
    await until(() => pose.every((p, i) => Math.abs(o.pwm[i]! - p) <= 1), 10_000, 'the bent pose');
    expect(await holdsStill(o, 2)).toBe(true);
    const z0 = tipZ();
    await page.getByTestId('hold-speed').selectOption('30');
    await z.hover();
    await page.mouse.down();
    await until(() => tipZ() > z0 + 5, 10_000, 'the tip to rise');
    const upAt = Date.now();
    await page.mouse.up();
    await until(() => o.commands(upAt).some((t) => t.includes('PDST')), 5000, 'the stop');
    expect(await holdsStill(o, 1)).toBe(true);
    expect(await holdsStill(o, 2)).toBe(true);
    expect(tipPose(arm5, o.pwm.slice(0, 6)).x).toBeCloseTo(250, -1); // x kept, within 5 mm
  });
});
