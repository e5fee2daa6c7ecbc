/// <reference lib="dom" />
/**
 * The 3D view drawn in a Web Worker (`?render=worker`, issue 17 items 2 and 3): the page says
 * so, the worker draws the arm and follows it, the orbit camera and a click on the floor work
 * from the page, and — with a 250 Hz stream, the health charts and the History panel open —
 * a click on Emergency stop and the Escape key each put `#255PDST!` on the broker (seen by a
 * Node MQTT subscriber, ArmObserver). With software WebGL (SwiftShader here) the worker paces
 * its frames and the Status panel says so; `?frames=full` draws every frame. `?render=main`
 * keeps the view on the page's thread.
 * Behaviour only: no timings are asserted (those are the bench's, bench/browser.ts).
 */
import type { Page } from '@playwright/test';
import { expect, test } from './fixtures.ts';
import { until } from './support/sim.ts';

interface WorkerHook {
  __armtwin: {
    viewer: {
      thread: string;
      software: boolean;
      renderedFrames: number;
      camera: { position: { x: number; y: number; z: number } };
      jointValues(which?: string): number[];
    };
    store: { rendered: Float64Array };
    target: { onPlace(fn: (x: number, y: number) => void): () => void };
  };
}

const frames = (page: Page) =>
  page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.renderedFrames);
const drawnBase = (page: Page) =>
  page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.jointValues()[0] ?? NaN);
const software = (page: Page) =>
  page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.software);

/** A jog of the base moves the arm as drawn (by the worker from the page's samples, or the page). */
async function drawnArmFollowsAJog(page: Page): Promise<void> {
  const before = await drawnBase(page);
  await page.getByRole('slider', { name: 'Base', exact: true }).fill('60');
  await expect
    .poll(async () => Math.abs((await drawnBase(page)) - before), { timeout: 10_000 })
    .toBeGreaterThan(0.3);
}

test.describe('rendering in a worker', () => {
  test.use({ simArgs: ['--rate', '250'], hudQuery: '&render=worker' });

  test('the worker draws the arm, follows it and orbits; the stop and Escape publish at once', async ({
    hud,
    arm,
  }) => {
    const { page } = hud;
    await expect(page.getByTestId('render-thread')).toContainText('Rendering: worker');
    expect(
      await page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.thread),
    ).toBe('worker');
    await expect(page.locator('#view canvas[data-render="worker"]')).toBeVisible();
    await expect.poll(() => frames(page)).toBeGreaterThan(0);

    await drawnArmFollowsAJog(page);
    // Software WebGL draws on the CPU: the worker paces its frames, and says what one costs.
    await expect(page.getByTestId('render-thread')).toHaveText(
      (await software(page))
        ? /^Rendering: worker, software WebGL paced to 50 % \(\d+ ms a frame\)$/
        : 'Rendering: worker',
    );

    // Orbiting: a drag on the view turns the page's camera, and the worker draws it.
    const view = page.locator('#view canvas');
    const box = (await view.boundingBox())!;
    const cam0 = await page.evaluate(() => ({
      ...(window as unknown as WorkerHook).__armtwin.viewer.camera.position,
    }));
    const shot0 = await view.screenshot();
    const frames0 = await frames(page);
    await page.mouse.move(box.x + box.width * 0.5, box.y + box.height * 0.6);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width * 0.35, box.y + box.height * 0.55, { steps: 8 });
    await page.mouse.up();
    const cam1 = await page.evaluate(() => ({
      ...(window as unknown as WorkerHook).__armtwin.viewer.camera.position,
    }));
    expect(Math.hypot(cam1.x - cam0.x, cam1.z - cam0.z)).toBeGreaterThan(0.05);
    await expect.poll(() => frames(page)).toBeGreaterThan(frames0);
    await expect.poll(async () => (await view.screenshot()).equals(shot0)).toBe(false);

    // The stop, with the stream at 250 Hz, the health charts and the History panel open.
    const history = page.locator('details.history > summary');
    if (await history.count()) await history.first().click();
    await expect(page.locator('.uplot canvas').first()).toBeVisible();
    const since = Date.now();
    await page.getByRole('button', { name: 'Emergency stop' }).click();
    await until(
      () => arm.observer.control(since).includes('#255PDST!'),
      5000,
      '#255PDST! after a click on Emergency stop',
    );
    expect(arm.observer.controlMessages(since).find((m) => m.text === '#255PDST!')?.qos).toBe(1);
    await expect(page.getByTestId('estop').locator('xpath=..')).toContainText('Stop sent');

    const again = Date.now();
    await page.keyboard.press('Escape');
    await until(
      () => arm.observer.control(again).includes('#255PDST!'),
      5000,
      '#255PDST! after Escape',
    );
    // One press, one stop: the click that follows the press is not a second one.
    expect(arm.observer.control(since).filter((t) => t === '#255PDST!')).toHaveLength(2);

    // Nothing waits: the stop's bytes are on the WebSocket before the pointerdown / keydown
    // handler returns (no frame, no timer, no promise in between).
    const onSocketInside = await page.evaluate(() => {
      const sends: string[] = [];
      const send = WebSocket.prototype.send;
      WebSocket.prototype.send = function (this: WebSocket, data) {
        sends.push(new TextDecoder().decode(data as ArrayBuffer | Uint8Array));
        return send.call(this, data);
      };
      const stopsIn = (fire: () => void): boolean => {
        sends.length = 0;
        fire();
        return sends.some((d) => d.includes('#255PDST!'));
      };
      try {
        const button = document.querySelector('[data-testid=estop]')!;
        return {
          press: stopsIn(() =>
            button.dispatchEvent(new PointerEvent('pointerdown', { bubbles: true, button: 0 })),
          ),
          escape: stopsIn(() =>
            window.dispatchEvent(new KeyboardEvent('keydown', { key: 'Escape', bubbles: true })),
          ),
        };
      } finally {
        WebSocket.prototype.send = send;
      }
    });
    expect(onSocketInside).toEqual({ press: true, escape: true });
  });

  test('a click on the floor places the Cartesian target (picked on the page)', async ({ hud }) => {
    const { page } = hud;
    await expect(page.getByTestId('render-thread')).toContainText('Rendering: worker');
    await page.evaluate(() => {
      const w = window as unknown as WorkerHook & { __placed?: number[] };
      w.__armtwin.target.onPlace((x, y) => (w.__placed = [x, y]));
    });
    const view = page.locator('#view canvas');
    const box = (await view.boundingBox())!;
    // Low in the view, in front of the arm: the floor.
    await page.mouse.click(box.x + box.width * 0.5, box.y + box.height * 0.85);
    await expect
      .poll(() => page.evaluate(() => (window as unknown as { __placed?: number[] }).__placed))
      .toHaveLength(2);
  });
});

test.describe('falling back to the main thread', () => {
  test('a render worker that fails to start hands the view to the main thread, which says so', async ({
    page,
    stack,
    arm,
  }) => {
    // The page's render worker is swapped for one whose script throws (a real worker error).
    await page.addInitScript(() => {
      const Real = window.Worker;
      window.Worker = class extends Real {
        constructor(url: string | URL, opts?: WorkerOptions) {
          const failing = URL.createObjectURL(
            new Blob(['throw new Error("simulated worker failure")'], { type: 'text/javascript' }),
          );
          super(opts?.name === 'render' ? failing : url, opts);
        }
      };
    });
    // No render= in the query: the default (a worker) is what fails.
    await page.goto(
      `${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=${arm.id}&role=operator`,
    );
    await expect(page.getByTestId('render-thread')).toContainText(
      'Rendering: main thread (worker failed:',
    );
    await expect(page.getByTestId('render-thread')).toContainText('simulated worker failure');
    await page.waitForFunction(
      () => (window as unknown as { __armtwin?: { ready?: boolean } }).__armtwin?.ready === true,
    );
    expect(
      await page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.thread),
    ).toBe('main');
    // A fresh canvas, drawn on the page, follows a jog.
    await expect(page.locator('#view canvas')).toHaveCount(1);
    await expect(page.locator('#view canvas[data-render="worker"]')).toHaveCount(0);
    await expect.poll(() => frames(page)).toBeGreaterThan(0);
    await drawnArmFollowsAJog(page);
  });
});

test.describe('rendering on the main thread', () => {
  test.use({ hudQuery: '&render=main' });

  test('?render=main keeps the view on the page and says so', async ({ hud }) => {
    const { page } = hud;
    await expect(page.getByTestId('render-thread')).toHaveText(
      /^Rendering: main thread(, software WebGL)?$/,
    );
    expect(
      await page.evaluate(() => (window as unknown as WorkerHook).__armtwin.viewer.thread),
    ).toBe('main');
    await expect.poll(() => frames(page)).toBeGreaterThan(0);
  });
});

test.describe('every frame drawn (?frames=full)', () => {
  test.use({ hudQuery: '&render=worker&frames=full' });

  test('software WebGL is not paced, says so, and the worker still follows the arm', async ({
    hud,
  }) => {
    const { page } = hud;
    await expect.poll(() => frames(page)).toBeGreaterThan(0);
    await drawnArmFollowsAJog(page);
    await expect(page.getByTestId('render-thread')).toHaveText(
      (await software(page)) ? 'Rendering: worker, software WebGL' : 'Rendering: worker',
    );
  });
});
