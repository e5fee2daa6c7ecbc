/// <reference lib="dom" />
/**
 * The HUD end to end, the arm's model: it renders (not a blank canvas), a mesh that fails is
 * named and the rest drawn, a robot description that fails shows an error. Real Mosquitto
 * (WebSockets), the real simulator (`armtwin sim`), the built HUD in Debian Chromium; the twin's
 * side through the page's read-only debug hook `window.__armtwin`.
 */
import type { Page } from '@playwright/test';
import { expect, shot, test, type HudWindow } from './fixtures.ts';

/** Luminance spread and coarse colour count of a PNG, decoded by the browser. */
async function pixelStats(page: Page, png: Buffer) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d')!;
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0;
    let sum2 = 0;
    let n = 0;
    let warm = 0; // the arm's orange and amber parts: nothing else in the scene is that colour
    const colours = new Set<number>();
    for (let i = 0; i < d.length; i += 4) {
      const [r, g, b] = [d[i]!, d[i + 1]!, d[i + 2]!];
      const l = 0.2126 * r + 0.7152 * g + 0.0722 * b;
      sum += l;
      sum2 += l * l;
      n++;
      colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
      if (r > 150 && r - b > 90 && g > 60) warm++;
    }
    const mean = sum / n;
    return { std: Math.sqrt(sum2 / n - mean * mean), colours: colours.size, warm };
  }, png.toString('base64'));
}

test('model: the arm renders, the canvas is not blank', async ({ hud }, testInfo) => {
  const { page } = hud;
  await expect(page.locator('#message')).toBeHidden();
  // A render worker's first frame (at the view's size) comes a moment after the page is ready.
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as HudWindow).__armtwin!.viewer.renderedFrames),
    )
    .toBeGreaterThan(0);
  const png = await page.locator('#view canvas').screenshot();
  const stats = await pixelStats(page, png);
  testInfo.annotations.push({ type: 'pixels', description: JSON.stringify(stats) });
  expect(stats.std).toBeGreaterThan(8);
  expect(stats.colours).toBeGreaterThan(100);
  expect(stats.warm).toBeGreaterThan(1000);
  await shot(page, testInfo, 'model');
});

test('model: a mesh that fails to load is named on the page, and the rest of the arm is drawn', async ({
  page,
  stack,
}, testInfo) => {
  await page.route('**/meshes/forearm.stl', (route) =>
    route.fulfill({ status: 404, body: 'gone' }),
  );
  await page.goto(`${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=nobody`);
  const note = page.getByTestId('mesh-failures');
  await expect(note).toContainText('1 mesh failed to load');
  await expect(note).toContainText('forearm.stl');
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  await expect(page.getByRole('button', { name: 'Emergency stop' })).toBeVisible();
  await shot(page, testInfo, 'mesh-error');
});

test('model: a robot description that fails to load shows an error, not a blank page', async ({
  page,
  stack,
}, testInfo) => {
  await page.route('**/armtwin5.urdf', (route) => route.fulfill({ status: 404, body: 'gone' }));
  await page.goto(`${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=nobody`);
  await expect(page.getByRole('alert')).toContainText('The arm model failed to load');
  await expect(page.getByRole('alert')).toContainText('armtwin5.urdf');
  await expect(page.getByRole('button', { name: 'Emergency stop' })).toBeVisible();
  await shot(page, testInfo, 'model-error');
});
