/**
 * The benchmark's browser: the system Chromium (tests/helpers/chromium.ts) launched headless by
 * playwright-core, one 1280×800 page with CDP's Performance domain on, page errors collected.
 * Shared by the browser and camera sections.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Browser, CDPSession, Page } from 'playwright-core';
import { CHROMIUM_ARGS, CHROMIUM_PATH } from '../../tests/helpers/chromium.ts';
import { until } from './proc.ts';
import { REPO } from './stack.ts';

/** The built HUD the sections serve. */
export const HUD_DIST = path.join(REPO, 'apps', 'web', 'dist');

/** Why the HUD cannot be benchmarked here, or null. */
export function hudPrecheck(): string | null {
  if (!fs.existsSync(path.join(HUD_DIST, 'index.html')))
    return 'HUD not built: apps/web/dist/index.html missing (npm run build)';
  if (!fs.existsSync(CHROMIUM_PATH)) return `${CHROMIUM_PATH} not found`;
  return null;
}

export interface HudBrowser {
  browser: Browser;
  page: Page;
  cdp: CDPSession;
  /** Uncaught page errors, in order. */
  pageErrors: string[];
}

export async function openHudBrowser(args: readonly string[] = CHROMIUM_ARGS): Promise<HudBrowser> {
  const { chromium } = await import('playwright-core');
  const browser = await chromium.launch({
    executablePath: CHROMIUM_PATH,
    headless: true,
    args: [...args],
    timeout: 60_000,
  });
  try {
    const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
    // tsx wraps named functions in __name(); the page needs it to exist.
    await context.addInitScript({ content: 'globalThis.__name = (f) => f;' });
    const page = await context.newPage();
    const pageErrors: string[] = [];
    page.on('pageerror', (e) => pageErrors.push(e.message));
    const cdp = await context.newCDPSession(page);
    await cdp.send('Performance.enable');
    return { browser, page, cdp, pageErrors };
  } catch (err) {
    await browser.close().catch(() => {});
    throw err;
  }
}

/** Waits until the HUD's debug hook says the model is loaded and the 3D view runs. */
export function hudReady(page: Page): Promise<unknown> {
  return page.waitForFunction(
    () => (window as { __armtwin?: { ready: boolean } }).__armtwin?.ready === true,
    null,
    { timeout: 60_000 },
  );
}

/** Opens the HUD at `url` and waits until it is connected and has taken in `minMessages` state messages. */
export async function openLiveHud(page: Page, url: string, minMessages: number): Promise<void> {
  await page.goto(url);
  await hudReady(page);
  const live = await until(
    () =>
      page.evaluate((min) => {
        const s = (
          window as unknown as {
            __armtwin: { store: { connection: string; counters: { messages: number } } };
          }
        ).__armtwin.store;
        return s.connection === 'connected' && s.counters.messages > min;
      }, minMessages),
    30_000,
    250,
  );
  if (!live) throw new Error('HUD never received the state stream');
}
