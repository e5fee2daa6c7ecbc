/// <reference lib="dom" />
/**
 * The page itself (issue 18): a page on another origin that frames the HUD of `armtwin up` (a
 * click on "Move" through an invisible frame) shows nothing of it, while the same page frames a
 * page without the headers as usual; the HUD opened directly runs with nothing blocked by its
 * own Content-Security-Policy.
 */
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import { cspViolations, expect, recordCspViolations, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { startUp, type UpProcess } from './support/up.ts';

/** Another site: `/` frames `hudUrl` and its own `/inner`. */
async function serveFramer(hudUrl: string) {
  const server = http.createServer((req, res) => {
    res.setHeader('content-type', 'text/html; charset=utf-8');
    if (req.url === '/inner') return res.end('<p id="inner">an ordinary page</p>');
    res.end(`<!doctype html><title>another site</title>
      <iframe name="inner" src="/inner" onload="window.innerLoaded = true"></iframe>
      <iframe name="hud" src="${hudUrl}" width="800" height="600"
        onload="window.hudLoaded = true"></iframe>`);
  });
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const { port } = server.address() as AddressInfo;
  return {
    url: `http://127.0.0.1:${port}/`,
    close: () => new Promise<void>((resolve) => server.close(() => resolve())),
  };
}

test.describe('the page itself', () => {
  let up: UpProcess | null = null;

  // eslint-disable-next-line no-empty-pattern
  test.beforeAll(async ({}, testInfo) => {
    test.setTimeout(150_000);
    ensureHudBuilt();
    up = await startUp(testInfo.outputPath('armtwin-up.log'));
  });

  test.afterAll(async () => {
    await up?.stop();
  });

  test('another site cannot frame the HUD', async ({ page }) => {
    const framer = await serveFramer(up!.url);
    try {
      await page.goto(framer.url);
      await page.waitForFunction(() => {
        const w = window as unknown as { innerLoaded?: boolean; hudLoaded?: boolean };
        return w.innerLoaded === true && w.hudLoaded === true;
      });
      // The ordinary page shows in its frame...
      await expect(page.frameLocator('iframe[name=inner]').locator('#inner')).toHaveText(
        'an ordinary page',
      );
      // ...the HUD does not: no page, no script of it runs in the frame.
      const frame = page.frame({ name: 'hud' })!;
      expect(frame).toBeTruthy();
      expect(frame.url()).not.toContain(up!.url);
      expect(await frame.locator('#hud, #view, [data-testid=estop]').count()).toBe(0);
      expect(
        await frame.evaluate(() => (window as unknown as HudWindow).__armtwin === undefined),
      ).toBe(true);
    } finally {
      await framer.close();
    }
  });

  test('opened directly, the HUD runs with nothing blocked by its policy', async ({ page }) => {
    await recordCspViolations(page);
    const res = await page.goto(up!.url);
    expect(res!.headers()['content-security-policy']).toContain("frame-ancestors 'none'");
    expect(res!.headers()['x-frame-options']).toBe('DENY');
    await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
    await expect(page.getByRole('form', { name: 'Log in' })).toBeVisible();
    await expect(page.getByTestId('estop')).toBeVisible();
    expect(await cspViolations(page)).toEqual([]);
  });

  test('with the 3D view drawn in a worker, the policy blocks nothing either', async ({ page }) => {
    await recordCspViolations(page);
    const url = new URL(up!.url);
    url.searchParams.set('render', 'worker');
    await page.goto(url.href);
    // `ready` comes once the worker has fetched and parsed the model under the worker's policy.
    await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
    await expect(page.getByTestId('render-thread')).toContainText('Rendering: worker');
    await expect
      .poll(() =>
        page.evaluate(() => (window as unknown as HudWindow).__armtwin!.viewer.renderedFrames),
      )
      .toBeGreaterThan(0);
    expect(await cspViolations(page)).toEqual([]);
  });
});
