/// <reference lib="dom" />
/**
 * Playwright fixtures for the HUD against the real stack:
 *  - `stack` (worker): a throwaway Mosquitto with WebSockets, and the built HUD served statically;
 *  - `arm` (test): a fresh `armtwin sim` on a unique arm id, already online, and an mqtt.js
 *    observer on that arm's topics;
 *  - `hud` (test): the page opened at `?broker=<ws url>&arm=<id>`, model loaded, data live.
 * Screenshots: Playwright's `screenshot: 'on'` keeps the last one; `shot()` attaches more.
 */
import { test as base, expect, type Page, type TestInfo } from '@playwright/test';
import { startMosquitto, type MosquittoService } from '../helpers/services.ts';
import { ensureHudBuilt, HUD_DIST } from './support/build-hud.ts';
import { serveStatic, type StaticServer } from './support/static-server.ts';
import { ArmObserver, startSim, until, type SimProcess } from './support/sim.ts';

export interface Stack {
  broker: MosquittoService;
  web: StaticServer;
}

export interface Arm {
  id: string;
  sim: SimProcess;
  observer: ArmObserver;
}

export interface Hud {
  page: Page;
  /** Extra query parameters for the HUD URL, set before the page opens (see `test.use`). */
  url: string;
}

let armCounter = 0;

export const test = base.extend<
  { arm: Arm; hud: Hud; hudQuery: string; simArgs: string[] },
  { stack: Stack }
>({
  stack: [
    // eslint-disable-next-line no-empty-pattern
    async ({}, use) => {
      ensureHudBuilt();
      const broker = await startMosquitto();
      const web = await serveStatic(HUD_DIST);
      try {
        await use({ broker, web });
      } finally {
        await web.close();
        await broker.dispose({ keepLogs: Boolean(process.env.ARMTWIN_KEEP_LOGS) });
      }
    },
    { scope: 'worker', timeout: 120_000 },
  ],

  simArgs: [[], { option: true }],

  arm: async ({ stack, simArgs }, use, testInfo) => {
    const id = `e2e-${process.pid}-${++armCounter}`;
    const observer = await ArmObserver.connect(stack.broker.url, id);
    const sim = startSim(stack.broker.url, id, testInfo.outputPath('sim.log'), simArgs);
    try {
      await until(
        () => observer.online === '1' && observer.pwm.length === 6,
        30_000,
        `sim ${id} online and streaming`,
      );
      await use({ id, sim, observer });
    } finally {
      await sim.stop();
      await observer.close();
      await testInfo
        .attach('sim.log', { path: sim.logFile, contentType: 'text/plain' })
        .catch(() => {});
    }
  },

  hudQuery: ['', { option: true }],

  hud: async ({ page, stack, arm, hudQuery }, use) => {
    // role=operator: the static server has no /api/whoami, and an unknown role only watches.
    // ARMTWIN_E2E_RENDER=worker runs every spec with the 3D view drawn in a worker.
    const render = process.env.ARMTWIN_E2E_RENDER
      ? `&render=${process.env.ARMTWIN_E2E_RENDER}`
      : '';
    const url = `${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=${arm.id}&role=operator${render}${hudQuery}`;
    page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
    await recordCspViolations(page);
    await page.goto(url);
    await page.waitForFunction(
      () => (window as unknown as HudWindow).__armtwin?.ready === true,
      null,
      { timeout: 30_000 },
    );
    await expect(page.getByTestId('broker-state')).toHaveText('connected');
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    await use({ page, url });
    // Nothing the page needs may be blocked by its Content-Security-Policy.
    expect(await cspViolations(page), 'Content-Security-Policy violations').toEqual([]);
  },
});

/**
 * Records the page's `securitypolicyviolation` events (what its Content-Security-Policy blocked)
 * from before its first script runs; read them with `cspViolations`.
 */
export async function recordCspViolations(page: Page): Promise<void> {
  await page.addInitScript(() => {
    const w = window as unknown as { __cspViolations: string[] };
    w.__cspViolations = [];
    window.addEventListener(
      'securitypolicyviolation',
      (e) => w.__cspViolations.push(`${e.effectiveDirective} blocked ${e.blockedURI || 'inline'}`),
      { capture: true },
    );
  });
}

/** What the page's policy blocked so far ([] for a page that has gone). */
export function cspViolations(page: Page): Promise<string[]> {
  return page
    .evaluate(() => (window as unknown as { __cspViolations?: string[] }).__cspViolations ?? [])
    .catch(() => []);
}

export { expect };

/** What the HUD exposes on `window.__armtwin` (read-only debug hook). */
export interface HudWindow {
  __armtwin?: {
    ready: boolean;
    store: {
      rendered: Float64Array;
      pwm: Float64Array;
      angle: Float64Array;
      commandedPwm: Float64Array;
    };
    viewer: { renderedFrames: number };
  };
}

/** The twin's drawn servo angles, degrees. */
export function renderedAngles(page: Page): Promise<number[]> {
  return page.evaluate(() =>
    Array.from((window as unknown as HudWindow).__armtwin!.store.rendered),
  );
}

/** Attaches a full-page screenshot to the report (and test-results) under `name`. */
export async function shot(page: Page, testInfo: TestInfo, name: string): Promise<void> {
  const file = testInfo.outputPath(`${name}.png`);
  await page.screenshot({ path: file });
  await testInfo.attach(name, { path: file, contentType: 'image/png' });
}
