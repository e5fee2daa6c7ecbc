/// <reference lib="dom" />
/**
 * Cameras in the HUD, end to end (issue 15; real Mosquitto, a real `serveCamera` with ffmpeg's
 * test source at 640×480, Debian Chromium on `http://127.0.0.1`, a secure context): announced
 * cameras appear as `Camera <label>` regions whose pixels change, over MJPEG and over
 * `h264-ws` (WebCodecs); removing the announcement removes the view; a stopped stream shows
 * "camera offline since …" and comes back by itself; a `javascript:` URL and a hostile label do
 * nothing. The announcements are published by the test (retained, as §7 says anyone may), so
 * each path is chosen on purpose. Every camera server started here is stopped.
 */
import type { Locator, Page } from '@playwright/test';
import mqtt, { type MqttClient } from 'mqtt';
import { serveCamera, type ServedCameras } from '@armtwin/camera';
import { LoginThrottle, loadUsers } from '@armtwin/auth';
import {
  cspViolations,
  expect,
  recordCspViolations,
  shot,
  test,
  type HudWindow,
} from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUp, USERS_FILE, type UpProcess } from './support/up.ts';

test.describe.configure({ mode: 'serial' });

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

function startCamera(armId: string, port = 0): Promise<ServedCameras> {
  return serveCamera({
    cameras: [{ armId, camId: 'front', label: 'Front', source: 'testsrc' }],
    port,
    mqttUrl: '', // the test announces, with the kinds it means to test
    backoff: { minMs: 200, maxMs: 2000, factor: 2, healthyMs: 5000 },
  });
}

/** A cheap fingerprint of what the view's canvas shows now. */
function canvasHash(view: Locator): Promise<number> {
  return view.locator('canvas').evaluate((c: HTMLCanvasElement) => {
    const d = c.getContext('2d')!.getImageData(0, 0, c.width, c.height).data;
    let h = 0;
    for (let i = 0; i < d.length; i += 7) h = (h * 31 + d[i]!) | 0;
    return h;
  });
}

async function expectPixelsChange(view: Locator): Promise<void> {
  await expect(view.getByTestId('camera-age')).toHaveText(/last frame \d+\.\d s ago/, {
    timeout: 20_000,
  });
  const first = await canvasHash(view);
  await expect.poll(() => canvasHash(view), { timeout: 10_000 }).not.toBe(first);
}

const cameraRegion = (page: Page, label: string) =>
  page.getByRole('region', { name: `Camera ${label}`, exact: true });

test.describe('cameras', () => {
  let cam: ServedCameras | null = null;
  let client: MqttClient | null = null;

  test.afterEach(async () => {
    await cam?.stop();
    cam = null;
    await client?.endAsync(true);
    client = null;
  });

  test('MJPEG and h264-ws cameras play; removal removes; a stopped stream goes offline and comes back', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    test.setTimeout(120_000);
    const { page } = hud;
    cam = await startCamera(arm.id);
    const port = cam.port;
    client = await mqtt.connectAsync(stack.broker.url, { reconnectPeriod: 0 });
    const announce = (camId: string, body: object | '') =>
      client!.publishAsync(
        `arm/${arm.id}/camera/${camId}`,
        body === '' ? '' : JSON.stringify(body),
        { qos: 1, retain: true },
      );
    const ws = cam.url.replace(/^http/, 'ws');
    await announce('mj', {
      url: `${cam.url}/camera/front.mjpeg`,
      kind: 'mjpeg',
      label: 'Front MJPEG',
    });
    await announce('h264', {
      url: `${ws}/camera/front.h264`,
      kind: 'h264-ws',
      label: 'Front H264',
    });

    const mj = cameraRegion(page, 'Front MJPEG');
    const h264 = cameraRegion(page, 'Front H264');
    await expect(mj).toBeVisible();
    await expect(h264).toBeVisible();
    await expect(mj).toHaveAttribute('data-kind', 'mjpeg');
    // A secure context (http://127.0.0.1): WebCodecs decodes the h264-ws stream.
    expect(await page.evaluate(() => typeof VideoDecoder)).toBe('function');
    await expect(h264).toHaveAttribute('data-kind', 'h264-ws');
    await expectPixelsChange(mj);
    await expectPixelsChange(h264);
    await mj.screenshot({ path: testInfo.outputPath('camera-mjpeg.png') });
    await h264.screenshot({ path: testInfo.outputPath('camera-h264.png') });
    await shot(page, testInfo, 'cameras-live');

    // The stream stops: each view says since when; a restarted server brings them back.
    await cam.stop();
    cam = null;
    await expect(mj.getByTestId('camera-age')).toHaveText(/camera offline since \d\d:\d\d:\d\d/, {
      timeout: 15_000,
    });
    await expect(h264.getByTestId('camera-age')).toHaveText(/camera offline since \d\d:\d\d:\d\d/, {
      timeout: 15_000,
    });
    await shot(page, testInfo, 'cameras-offline');
    await sleep(500);
    cam = await startCamera(arm.id, port);
    await expectPixelsChange(mj);
    await expectPixelsChange(h264);

    // An empty retained payload removes the camera, and its view.
    await announce('mj', '');
    await announce('h264', '');
    await expect(mj).toHaveCount(0);
    await expect(h264).toHaveCount(0);
  });

  test('a folded Cameras panel closes the stream and the picture holds; unfolded, it plays again', async ({
    hud,
    arm,
    stack,
  }) => {
    test.setTimeout(90_000);
    const { page } = hud;
    cam = await startCamera(arm.id);
    client = await mqtt.connectAsync(stack.broker.url, { reconnectPeriod: 0 });
    const topic = `arm/${arm.id}/camera/mj`;
    // No pose: no screen in the 3D view, so the panel is the only place it is shown.
    await client.publishAsync(
      topic,
      JSON.stringify({ url: `${cam.url}/camera/front.mjpeg`, kind: 'mjpeg', label: 'Front' }),
      { qos: 1, retain: true },
    );
    const view = cameraRegion(page, 'Front');
    await expectPixelsChange(view);
    const viewers = () => cam!.server.stats().cameras[0]!.streams.mjpeg!.viewers.length;
    expect(viewers()).toBe(1);
    const fold = page.locator('.panel.cameras > summary');

    await fold.click();
    await expect(view).toBeHidden();
    // The server sees the request closed, and the page draws no more frames (the folded view is
    // out of the accessibility tree: found by its camera id).
    await expect.poll(viewers, { timeout: 10_000 }).toBe(0);
    const folded = page.locator('section[data-camid="mj"]');
    const still = await canvasHash(folded);
    await sleep(1500);
    expect(await canvasHash(folded)).toBe(still);

    await fold.click();
    await expect.poll(viewers, { timeout: 10_000 }).toBe(1);
    await expectPixelsChange(view);
    await client.publishAsync(topic, '', { qos: 1, retain: true });
    await expect(view).toHaveCount(0);
  });

  test('a posed camera has a screen in the 3D view, and the view looks through it', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    test.setTimeout(90_000);
    const { page } = hud;
    cam = await startCamera(arm.id);
    client = await mqtt.connectAsync(stack.broker.url, { reconnectPeriod: 0 });
    const topic = `arm/${arm.id}/camera/front`;
    await client.publishAsync(
      topic,
      JSON.stringify({
        url: `${cam.url}/camera/front.mjpeg`,
        kind: 'mjpeg',
        label: 'Front',
        pose: { position: [600, -400, 450], lookAt: [0, 0, 220] },
        fovDeg: 50,
      }),
      { qos: 1, retain: true },
    );
    const view = cameraRegion(page, 'Front');
    await expectPixelsChange(view);
    const fov = () =>
      page.evaluate(
        () =>
          (window as unknown as { __armtwin: { viewer: { camera: { fov: number } } } }).__armtwin
            .viewer.camera.fov,
      );
    const before = await fov();
    await shot(page, testInfo, 'camera-screen-in-scene');
    await view.getByRole('button', { name: 'View through this camera' }).click();
    await expect(view.getByRole('button', { name: 'Back to the 3D view' })).toHaveAttribute(
      'aria-pressed',
      'true',
    );
    expect(await fov()).toBe(50);
    await sleep(1500);
    await shot(page, testInfo, 'camera-view-through');
    await view.getByRole('button', { name: 'Back to the 3D view' }).click();
    expect(await fov()).toBe(before);
    await client.publishAsync(topic, '', { qos: 1, retain: true });
    await expect(view).toHaveCount(0);
  });

  test('a javascript: URL and a hostile label do nothing', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    const { page } = hud;
    const dialogs: string[] = [];
    page.on('dialog', (d) => {
      dialogs.push(d.message());
      void d.dismiss();
    });
    client = await mqtt.connectAsync(stack.broker.url, { reconnectPeriod: 0 });
    const topic = (c: string) => `arm/${arm.id}/camera/${c}`;
    await client.publishAsync(
      topic('evil-url'),
      JSON.stringify({ url: 'javascript:alert(1)', kind: 'mjpeg', label: 'Evil URL' }),
      { qos: 1, retain: true },
    );
    const hostile = '<img src=x onerror="window.__pwned=1;alert(2)">';
    await client.publishAsync(
      topic('evil-label'),
      JSON.stringify({ url: 'http://127.0.0.1:9/camera/x.mjpeg', kind: 'mjpeg', label: hostile }),
      { qos: 1, retain: true },
    );
    const view = cameraRegion(page, hostile);
    await expect(view).toBeVisible();
    await expect(view.locator('.camera-label')).toHaveText(hostile);
    await expect(page.locator('.panel.cameras img')).toHaveCount(0);
    await expect(cameraRegion(page, 'Evil URL')).toHaveCount(0);
    await expect(page.getByTestId('camera-rejects')).toContainText('unsupported-url 1');
    // Nothing listens on port 9: the view says it is offline, and the page goes on.
    await expect(view.getByTestId('camera-age')).toHaveText(/camera offline since/, {
      timeout: 15_000,
    });
    expect(await page.evaluate(() => (window as { __pwned?: number }).__pwned)).toBeUndefined();
    expect(dialogs).toEqual([]);
    await shot(page, testInfo, 'cameras-hostile');
    for (const c of ['evil-url', 'evil-label'])
      await client.publishAsync(topic(c), '', { qos: 1, retain: true });
  });

  test('with log-ins: a viewer sees the cameras, an anonymous page does not', async ({
    page,
  }, testInfo) => {
    test.setTimeout(150_000);
    ensureHudBuilt();
    let up: UpProcess | null = null;
    let device: MqttClient | null = null;
    try {
      // The camera server is on another port: name it to the HUD's Content-Security-Policy.
      up = await startUp(testInfo.outputPath('armtwin-up.log'), [
        '--csp-sources',
        'http://127.0.0.1:* ws://127.0.0.1:*',
      ]);
      // The camera server logs in to the broker as the arm's device, and asks its viewers to log in.
      cam = await serveCamera({
        cameras: [{ armId: 'arm1', camId: 'front', label: 'Front', source: 'testsrc' }],
        port: 0,
        access: { logins: new LoginThrottle(loadUsers(USERS_FILE)), token: '' },
        mqttUrl: up.mqttUrl,
        username: 'arm1',
        password: demoPassword('arm1'),
      });
      await cam.announced;
      // The same server's MJPEG stream alone, announced by the device too.
      device = await mqtt.connectAsync(up.mqttUrl, {
        reconnectPeriod: 0,
        username: 'arm1',
        password: demoPassword('arm1'),
      });
      await device.publishAsync(
        'arm/arm1/camera/front-mjpeg',
        JSON.stringify({
          url: `${cam.url}/camera/front.mjpeg`,
          kind: 'mjpeg',
          label: 'Front MJPEG',
        }),
        { qos: 1, retain: true },
      );

      page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
      await recordCspViolations(page);
      await page.goto(up.url);
      await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
      const form = page.getByRole('form', { name: 'Log in' });
      await expect(form).toBeVisible();
      await sleep(2000);
      await expect(page.getByRole('region', { name: /^Camera / })).toHaveCount(0);

      await form.getByLabel('Username').fill('viewer');
      await form.getByLabel('Password').fill(demoPassword('viewer'));
      await form.getByRole('button', { name: 'Log in' }).click();
      await expect(page.getByTestId('signed-in-as')).toHaveText('Signed in as viewer, viewer.');
      const h264 = cameraRegion(page, 'Front');
      const mj = cameraRegion(page, 'Front MJPEG');
      await expect(h264).toHaveAttribute('data-kind', 'h264-ws');
      await expect(mj).toHaveAttribute('data-kind', 'mjpeg');
      await expectPixelsChange(h264);
      await expectPixelsChange(mj);
      await shot(page, testInfo, 'cameras-viewer');
      expect(await cspViolations(page), 'Content-Security-Policy violations').toEqual([]);
    } finally {
      await device
        ?.publishAsync('arm/arm1/camera/front-mjpeg', '', { qos: 1, retain: true })
        .catch(() => {});
      await device?.endAsync(true);
      await cam?.stop();
      cam = null;
      await up?.stop();
    }
  });
});
