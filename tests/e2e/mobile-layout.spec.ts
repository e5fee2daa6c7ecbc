/// <reference lib="dom" />
/**
 * The HUD on a phone (390×844, touch) and a tablet (1024×768, touch), end to end against the
 * real stack (Mosquitto, `armtwin sim`, Chromium): the 3D view stays on screen and uncovered;
 * the emergency stop is always on screen, at least 44 px, never under the sheet, and stops the
 * arm when tapped; the panels fold into a bottom sheet raised one tab at a time (tap or swipe),
 * their inputs inside the screen; and a finger held on a jog button moves the joint only while
 * it touches. What the arm does is read by a raw MQTT subscriber.
 */
import type { Page } from '@playwright/test';
import { expect, shot, test, type Arm } from './fixtures.ts';
import { holdsStill, movedFrom, movesOf } from './support/arm-motion.ts';
import { onScreen } from './support/on-screen.ts';
import { until } from './support/sim.ts';

const BASE = 0;
const PHONE = { viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true };
const TABLET = { viewport: { width: 1024, height: 768 }, hasTouch: true };

const canvas = (page: Page) => page.locator('#view canvas');
const stopButton = (page: Page) => page.getByRole('button', { name: 'Emergency stop' });
const tabBar = (page: Page) => page.getByRole('navigation', { name: 'Panels' });
const tab = (page: Page, name: string) => tabBar(page).getByRole('button', { name, exact: true });

/** The 3D view: a real area inside the screen, nothing drawn over its centre. */
async function expectViewOnScreen(page: Page): Promise<void> {
  const view = await onScreen(canvas(page));
  expect(view.width * view.height, 'the 3D view has a real area').toBeGreaterThan(300 * 250);
  expect(view.inside, 'the 3D view lies inside the screen').toBe(true);
  expect(view.uncovered, `nothing over the 3D view's centre (on top: ${view.onTop})`).toBe(true);
}

/** The stop: inside the screen, finger-sized, nothing over it. */
async function expectStopOnScreen(page: Page): Promise<void> {
  const stop = await onScreen(stopButton(page));
  expect(stop.inside, 'the stop lies inside the screen').toBe(true);
  expect(Math.min(stop.width, stop.height), 'a finger-sized stop').toBeGreaterThanOrEqual(44);
  expect(stop.uncovered, `nothing over the stop (on top: ${stop.onTop})`).toBe(true);
}

/** A tap on the stop reaches the arm as `#255PDST!`. */
async function expectStopWorks(page: Page, arm: Arm): Promise<void> {
  const since = Date.now();
  await stopButton(page).tap();
  await until(() => arm.observer.commands(since).includes('#255PDST!'), 5000, 'the stop');
  await expect(page.getByRole('banner').getByRole('status')).toContainText('Stop sent');
}

/** Every input of a panel lies inside the screen with nothing over it, wide enough to read. */
async function expectInputsFit(page: Page, panel: string): Promise<void> {
  const inputs = page.getByRole('region', { name: panel }).locator('input');
  expect(await inputs.count()).toBeGreaterThan(0);
  for (const input of await inputs.all()) {
    await input.scrollIntoViewIfNeeded();
    const box = await onScreen(input);
    const label = await input.evaluate((el) => el.closest('label')?.textContent ?? el.outerHTML);
    expect(box.inside, `${label}: inside the screen`).toBe(true);
    expect(box.uncovered, `${label}: nothing over it (on top: ${box.onTop})`).toBe(true);
    expect(box.width, `${label}: wide enough for "-150"`).toBeGreaterThanOrEqual(60);
  }
}

/** Puts a finger on `target`'s centre (CDP touch events; the page sees pointer events). */
async function touchDown(
  page: Page,
  target: { x: number; y: number; width: number; height: number },
) {
  const cdp = await page.context().newCDPSession(page);
  const point = { x: target.x + target.width / 2, y: target.y + target.height / 2 };
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: [point] });
  return { cdp, point };
}

/** A finger swipe of `dy` px from `target`'s centre, in small steps. */
async function swipe(page: Page, target: Awaited<ReturnType<typeof onScreen>>, dy: number) {
  const { cdp, point } = await touchDown(page, target);
  for (let i = 1; i <= 5; i++) {
    const p = { x: point.x, y: point.y + (dy * i) / 5 };
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: [p] });
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
}

/**
 * Holds a finger on "Hold Base +": the base moves while it touches; lifted, the HUD sends the
 * stop and the base holds still, with no more moves.
 */
async function expectTouchHoldJogs(page: Page, arm: Arm): Promise<void> {
  const o = arm.observer;
  const plus = page.getByRole('button', { name: 'Hold Base +' });
  await plus.scrollIntoViewIfNeeded();
  const box = await onScreen(plus);
  expect(box.inside && box.uncovered, `Hold Base + on screen (on top: ${box.onTop})`).toBe(true);
  expect(Math.min(box.width, box.height), 'a finger-sized jog button').toBeGreaterThanOrEqual(44);
  const start = o.pwm[BASE]!;
  const { cdp } = await touchDown(page, box);
  const a = await movedFrom(o, BASE, start);
  expect(a).toBeGreaterThan(start);
  expect(await movedFrom(o, BASE, a)).toBeGreaterThan(a); // still going while the finger stays
  await expect(page.getByTestId('hold-state')).toHaveText('moving: Base');
  const liftedAt = Date.now();
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
  await until(() => o.commands(liftedAt).includes('#000PDST!'), 5000, 'the stop on lift');
  expect(await holdsStill(o, BASE)).toBe(true);
  const stillAt = Date.now();
  expect(await holdsStill(o, BASE)).toBe(true);
  expect(movesOf(o, BASE, stillAt)).toEqual([]);
  await expect(page.getByTestId('hold-state')).toHaveText('hold − / + to move');
}

test.describe('phone 390×844', () => {
  test.use(PHONE);

  test('the arm and the stop are on screen; the panels fold into a sheet raised from the tab bar', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    // The sheet lowered: the 3D view, the stop and the tab bar; no panel over the arm.
    await expectViewOnScreen(page);
    await expectStopOnScreen(page);
    await expect(page.getByRole('region', { name: 'Jog' })).toBeHidden();
    const tabs = tabBar(page).getByRole('button');
    await expect(tabs).toHaveText(['Jog', 'Target', 'View', 'Arm', 'Setup']);
    for (const tab of await tabs.all()) {
      const box = await onScreen(tab);
      expect(box.inside && box.uncovered && box.height >= 44, `tab ${box.onTop}`).toBe(true);
    }
    await shot(page, testInfo, 'phone-lowered');

    // A tap on Target raises the sheet on the Cartesian target (and its fellows) alone.
    const target = tab(page, 'Target');
    await target.tap();
    await expect(target).toHaveAttribute('aria-expanded', 'true');
    await expect(page.getByRole('region', { name: 'Cartesian target' })).toBeVisible();
    await expect(page.getByRole('region', { name: 'Jog' })).toBeHidden();
    await expectInputsFit(page, 'Cartesian target');
    // The arm keeps the top of the screen; the sheet is below it, the stop over it.
    await expect.poll(async () => (await onScreen(canvas(page))).uncovered).toBe(true);
    await expectViewOnScreen(page);
    const sheetTop = (await page.locator('#hud-sheet').boundingBox())!.y;
    const view = (await canvas(page).boundingBox())!;
    expect(view.y + view.height, 'the 3D view ends where the sheet starts').toBeLessThanOrEqual(
      sheetTop + 1,
    );
    // Scrolled to its end, the sheet still leaves the stop alone.
    await page.locator('#hud-sheet').evaluate((el) => el.scrollTo(0, el.scrollHeight));
    await expectStopOnScreen(page);
    await shot(page, testInfo, 'phone-target');

    // One tab at a time: Arm replaces Target.
    await tab(page, 'Arm').tap();
    await expect(page.getByRole('region', { name: /^Status/ })).toBeVisible();
    await expect(page.getByRole('region', { name: 'Cartesian target' })).toBeHidden();
    await expect(target).toHaveAttribute('aria-expanded', 'false');

    // The handle lowers the sheet (tap), a swipe up on the tab bar raises it on the last tab, a
    // swipe down on the handle lowers it again.
    await page.getByRole('button', { name: 'Lower the panels' }).tap();
    await expect(page.locator('#hud-sheet')).toBeHidden();
    await swipe(page, await onScreen(tabBar(page)), -120);
    await expect(page.getByRole('region', { name: /^Status/ })).toBeVisible();
    await swipe(page, await onScreen(page.getByRole('button', { name: 'Lower the panels' })), 150);
    await expect(page.locator('#hud-sheet')).toBeHidden();
    await expectViewOnScreen(page);

    // The stop, tapped, stops the arm.
    await expectStopWorks(page, arm);
  });

  test('a finger held on a jog button moves the joint; lifted, it stops', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    await tab(page, 'Jog').tap();
    await expect(page.getByRole('region', { name: 'Jog' })).toBeVisible();
    await expectViewOnScreen(page);
    await expectStopOnScreen(page);
    await page.getByTestId('hold-speed').selectOption('30');
    await expectTouchHoldJogs(page, arm);
    await shot(page, testInfo, 'phone-jog');
  });
});

test.describe('tablet 1024×768', () => {
  test.use(TABLET);

  test('the arm, the stop and the panels share the screen; touch-and-hold jogs', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    await expectViewOnScreen(page);
    await expectStopOnScreen(page);
    // Wide enough for the columns: every panel is out, no tab bar.
    await expect(tabBar(page)).toBeHidden();
    await expect(page.getByRole('region', { name: 'Jog' })).toBeVisible();
    await expectInputsFit(page, 'Cartesian target');
    await page.getByTestId('hold-speed').selectOption('30');
    await expectTouchHoldJogs(page, arm);
    await shot(page, testInfo, 'tablet');
    await expectStopWorks(page, arm);
  });
});
