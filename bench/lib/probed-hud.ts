/**
 * The HUD under the page probe (./page-probe.ts), as the browser and twin sections drive it:
 * opened live with the probe installed, then a measurement window between `startProbe` and
 * `stopProbe`, whose result is every frame the probe recorded.
 */
import type { Page } from 'playwright-core';
import { installProbe, type ProbeResult } from './page-probe.ts';
import { openLiveHud } from './hud-browser.ts';

type ProbeWindow = { __benchProbe: { start(): void; stop(): ProbeResult } };

/**
 * Opens the HUD at `url`, waits until it has taken in `minMessages` state messages, and installs
 * the probe with room for `maxFrames` frames.
 */
export async function openProbedHud(
  page: Page,
  url: string,
  minMessages: number,
  maxFrames: number,
): Promise<void> {
  await openLiveHud(page, url, minMessages);
  if (!(await page.evaluate(installProbe, maxFrames)))
    throw new Error('window.__armtwin has no store/viewer.renderer to probe');
}

export function startProbe(page: Page): Promise<void> {
  return page.evaluate(() => (window as unknown as ProbeWindow).__benchProbe.start());
}

export function stopProbe(page: Page): Promise<ProbeResult> {
  return page.evaluate(() => (window as unknown as ProbeWindow).__benchProbe.stop());
}
