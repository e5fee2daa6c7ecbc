/// <reference lib="dom" />
/**
 * Gamepads end to end (issue 18; real Mosquitto, a real `armtwin sim`, Chromium): a scripted
 * gamepad is injected into the page (`navigator.getGamepads` overridden before the HUD loads,
 * `gamepadconnected` dispatched). The sticks jog only while the enabling trigger is held; its
 * stop button sends the emergency stop; a gamepad that disconnects with the stick pushed leaves
 * the arm stopped; the mapping is on screen, can be changed, and is kept across a reload.
 */
import type { Page } from '@playwright/test';
import { expect, shot, test as base, type HudWindow } from './fixtures.ts';
import { holdsStill, movedFrom, movesOf, nextPulses } from './support/arm-motion.ts';
import { until } from './support/sim.ts';

/** The page's scripted gamepad (standard layout: axis 0 = left stick x, button 7 = RT, 1 = B). */
interface ScriptedPad {
  set(axes: number[], pressed: number[]): void;
  connect(): void;
  disconnect(): void;
}

const test = base.extend({
  page: async ({ page }, use) => {
    await page.addInitScript(() => {
      const pad = {
        id: 'Scripted gamepad (STANDARD GAMEPAD)',
        index: 0,
        connected: false,
        mapping: 'standard',
        timestamp: 0,
        axes: [0, 0, 0, 0],
        buttons: Array.from({ length: 17 }, () => ({ pressed: false, touched: false, value: 0 })),
      };
      const fire = (type: string) => {
        const e = new Event(type);
        Object.defineProperty(e, 'gamepad', { value: pad });
        window.dispatchEvent(e);
      };
      Object.defineProperty(Navigator.prototype, 'getGamepads', {
        configurable: true,
        value: () => [pad.connected ? pad : null, null, null, null],
      });
      const scripted: ScriptedPad = {
        set(axes, pressed) {
          pad.axes = [...axes];
          pad.buttons = pad.buttons.map((_, i) => ({
            pressed: pressed.includes(i),
            touched: pressed.includes(i),
            value: pressed.includes(i) ? 1 : 0,
          }));
          pad.timestamp = performance.now();
        },
        connect() {
          pad.connected = true;
          fire('gamepadconnected');
        },
        disconnect() {
          pad.connected = false;
          fire('gamepaddisconnected');
        },
      };
      (window as unknown as { __pad: ScriptedPad }).__pad = scripted;
    });
    await use(page);
  },
});

const BASE = 0;
const ELBOW = 2;
const RT = 7;
const B = 1;

const pad = (page: Page, axes: number[], pressed: number[] = []) =>
  page.evaluate(
    ([a, p]) => (window as unknown as { __pad: ScriptedPad }).__pad.set(a!, p!),
    [axes, pressed],
  );
const padDo = (page: Page, what: 'connect' | 'disconnect') =>
  page.evaluate((w) => (window as unknown as { __pad: ScriptedPad }).__pad[w](), what);

test.describe('gamepad', () => {
  test('the stick jogs only with the trigger held; letting go of it stops the arm', async ({
    hud: { page },
    arm,
  }, testInfo) => {
    const o = arm.observer;
    await padDo(page, 'connect');
    await expect(page.getByTestId('gamepad-state')).toContainText('Scripted gamepad');
    await expect(page.getByTestId('gamepad-state')).toContainText('hold Right trigger to jog');

    // Stick pushed, trigger not held: nothing is sent, nothing moves.
    const start = o.pwm[BASE]!;
    const pushedAt = Date.now();
    await pad(page, [1, 0, 0, 0]);
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(o.pwm[BASE]).toBe(start);
    expect(movesOf(o, BASE, pushedAt), 'no move without the enabling trigger').toEqual([]);

    // Trigger held: the base moves, and keeps moving.
    await pad(page, [1, 0, 0, 0], [RT]);
    await expect(page.getByTestId('gamepad-state')).toContainText('enabled');
    const a = await movedFrom(o, BASE, start);
    await movedFrom(o, BASE, a);
    await page.getByTestId('gamepad-section').locator('summary').click();
    await shot(page, testInfo, 'gamepad-enabled');

    // Trigger let go, stick still pushed: stopped at once, and no keep-alive after.
    const letGoAt = Date.now();
    await pad(page, [1, 0, 0, 0]);
    await until(() => o.commands(letGoAt).includes('#000PDST!'), 5000, 'the stop');
    expect(await holdsStill(o, BASE)).toBe(true);
    const stillAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stillAt)).toEqual([]);
  });

  test('the stop button sends the emergency stop; the sticks stay dead until the trigger is pressed again', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    await padDo(page, 'connect');
    const start = o.pwm[BASE]!;
    await pad(page, [-1, 0, 0, 0], [RT]);
    await movedFrom(o, BASE, await movedFrom(o, BASE, start));

    const stopAt = Date.now();
    await pad(page, [-1, 0, 0, 0], [RT, B]);
    await until(() => o.commands(stopAt).includes('#255PDST!'), 5000, 'the emergency stop');
    await expect(page.getByTestId('gamepad-stopped')).toContainText(
      'Emergency stop from the gamepad',
    );
    // The trigger and the stick are still held: the arm stays stopped.
    await pad(page, [-1, 0, 0, 0], [RT]);
    expect(await holdsStill(o, BASE)).toBe(true);
    const stillAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stillAt), 'no move after the stop').toEqual([]);

    // Trigger released and pressed again: it jogs again.
    await pad(page, [-1, 0, 0, 0]);
    await nextPulses(o, BASE, 3);
    const here = o.pwm[BASE]!;
    await pad(page, [-1, 0, 0, 0], [RT]);
    await movedFrom(o, BASE, here);
    await pad(page, [0, 0, 0, 0]);
  });

  test('a gamepad that disconnects with the stick pushed leaves the arm stopped', async ({
    hud: { page },
    arm,
  }) => {
    const o = arm.observer;
    await padDo(page, 'connect');
    const start = o.pwm[BASE]!;
    await pad(page, [1, 0, 0, 0], [RT]);
    await movedFrom(o, BASE, await movedFrom(o, BASE, start));
    const goneAt = Date.now();
    await padDo(page, 'disconnect');
    await until(() => o.commands(goneAt).includes('#000PDST!'), 5000, 'the stop');
    expect(await holdsStill(o, BASE)).toBe(true);
    const stillAt = Date.now();
    expect(await holdsStill(o, BASE)).toBe(true);
    expect(movesOf(o, BASE, stillAt)).toEqual([]);
    await expect(page.getByTestId('gamepad-state')).toContainText('none connected');
  });

  test('the mapping is shown, can be changed, and is kept across a reload', async ({
    hud: { page, url },
    arm,
  }) => {
    const o = arm.observer;
    const section = page.getByTestId('gamepad-section');
    await section.locator('summary').click();
    const drives = section.getByLabel('Left stick ←→ drives');
    await expect(drives).toHaveValue('0'); // Base
    await expect(section.getByLabel('Enabling button')).toHaveValue(String(RT));
    await expect(section.getByLabel('Emergency stop button')).toHaveValue(String(B));

    // The enable and stop buttons may not be one button: refused, said, not saved.
    await section.getByLabel('Emergency stop button').selectOption(String(RT));
    await expect(section.getByRole('alert')).toContainText('must differ');
    await section.getByLabel('Emergency stop button').selectOption(String(B));
    await expect(section.getByRole('alert')).toHaveCount(0);

    await drives.selectOption({ label: 'Elbow' });
    await page.reload();
    await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
    await expect(page).toHaveURL(url);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    await page.getByTestId('gamepad-section').locator('summary').click();
    await expect(
      page.getByTestId('gamepad-section').getByLabel('Left stick ←→ drives'),
    ).toHaveValue(String(ELBOW));

    // The left stick now drives the elbow, not the base.
    await padDo(page, 'connect');
    const base0 = o.pwm[BASE]!;
    const elbow0 = o.pwm[ELBOW]!;
    const since = Date.now();
    await pad(page, [1, 0, 0, 0], [RT]);
    await movedFrom(o, ELBOW, elbow0);
    expect(movesOf(o, BASE, since)).toEqual([]);
    expect(o.pwm[BASE]).toBe(base0);
    await pad(page, [0, 0, 0, 0]);
  });
});
