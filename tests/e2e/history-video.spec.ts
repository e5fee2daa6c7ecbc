/// <reference lib="dom" />
/**
 * One timeline (issue 32 item 2), end to end: real Mosquitto, the real simulator, the real
 * middleware with InfluxDB recording a real camera server (ffmpeg's test source, H.264) in 2 s
 * MP4 segments (./history-fixtures.ts), the built HUD in the system Chromium. A few seconds are
 * recorded with the elbow moving and the camera server down for a while; the History replay then
 * plays the recorded video beside the amber arm: at a paused replay time T the <video>'s media
 * time + its segment's start is T within one frame while the replay's pose is the stored pose
 * of T; playing moves the video at the replay's speed; in the camera's gap "no recording" shows;
 * the segment after the one playing is fetched before the replay reaches it; the History charts
 * mark the replay's instant. A second camera that offers only MJPEG (the
 * first one's MJPEG stream, announced as it is) is recorded as its JPEGs (`.mjpeg` segments) and the replay shows, at T, the recorded JPEG of T
 * (the last one at or before it) in an <img>.
 */
import type { Page } from '@playwright/test';
import {
  createMultipartParser,
  MJPEG_BOUNDARY,
  serveCamera,
  type ServedCameras,
} from '@armtwin/camera';
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import { shot } from './fixtures.ts';
import { expect, test, type StorageStack } from './history-fixtures.ts';
import { until } from './support/sim.ts';
import { freePort } from '../helpers/services.ts';

const FPS = 30;
const FRAME_MS = 1000 / FPS;
/** 45° as stored: the angle of the pulse the sim reports (whole µs). */
const ELBOW_45 = angleFromPwm(pwmFromAngle(45, 1), 1);

interface Listed {
  name: string;
  startMs: number;
  endMs: number;
}
interface ReplayHook {
  __armtwin?: {
    replay: { angles: Float64Array; clock: { position: number } };
    history: { charts: Record<string, { replayAt: number | null } | undefined> };
  };
}

const cameras: ServedCameras[] = [];
test.afterAll(async () => {
  await Promise.all(cameras.map((c) => c.stop()));
});

async function startCamera(stack: StorageStack, armId: string, port: number) {
  const c = await serveCamera({
    cameras: [
      { armId, camId: 'front', label: 'Front', source: 'testsrc', kinds: ['h264-ws', 'mjpeg'] },
      // front's MJPEG stream announced as it is (no second ffmpeg): a camera offering only MJPEG
      {
        armId,
        camId: 'side',
        label: 'Side',
        source: `http://127.0.0.1:${port}/camera/front.mjpeg`,
      },
    ],
    port,
    mqttUrl: stack.broker.url,
  });
  cameras.push(c);
  await c.announced;
  return c;
}

async function segments(stack: StorageStack, armId: string, cam = 'front'): Promise<Listed[]> {
  const res = await fetch(`${stack.apiUrl}/arms/${armId}/cameras/${cam}/segments`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { segments: Listed[] }).segments;
}

/** The time of the MJPEG camera's recorded JPEG shown at `t`: the last at or before it. */
async function jpegAt(stack: StorageStack, armId: string, t: number): Promise<number> {
  const s = (await segments(stack, armId, 'side')).find((x) => x.startMs <= t && t <= x.endMs)!;
  const bytes = await (
    await fetch(`${stack.apiUrl}/arms/${armId}/cameras/side/segments/${s.name}`)
  ).arrayBuffer();
  const times: number[] = [];
  const parser = createMultipartParser({
    boundary: MJPEG_BOUNDARY,
    onPart: (p) => times.push(Number(p.headers['x-timestamp'])),
  });
  parser.feed(new Uint8Array(bytes));
  return times.filter((x) => x <= t).at(-1)!;
}

/** The MJPEG camera's <img>: the time of the JPEG it shows, and whether it is hidden. */
const jpegNow = (page: Page) =>
  page
    .getByTestId('replay-video-side')
    .locator('img')
    .evaluate((i: HTMLImageElement) => ({
      frameAt: Number(i.dataset.frameAt),
      shown: !i.hidden && i.complete && i.naturalWidth > 0,
    }));

const covered = (list: Listed[], t: number) => list.some((s) => s.startMs <= t && t <= s.endMs);

/** What the replay's <video> shows now: its segment's start + media time, and its state. */
const videoNow = (page: Page) =>
  page
    .getByTestId('replay-video-front')
    .locator('video')
    .evaluate((v: HTMLVideoElement) => ({
      shownMs: Number(v.dataset.segmentStart) + v.currentTime * 1000,
      paused: v.paused,
      rate: v.playbackRate,
      decoded: v.readyState >= HTMLMediaElement.HAVE_CURRENT_DATA,
      hidden: v.hidden,
    }));

interface Crossing {
  /** The page's clock (performance.now()) just before Play is pressed… */
  armedAt?: number;
  /** …when the replay first reached the segment… */
  crossedAt?: number;
  /** …and when the <video> first held that segment. */
  shownAt?: number;
}

/** Notes, in the page, when the replay reaches the segment starting at `t` and when it shows. */
const watchCrossing = (page: Page, t: number) =>
  page.evaluate((at) => {
    const w = window as unknown as ReplayHook & { __crossing: Crossing };
    const c: Crossing = (w.__crossing = { armedAt: performance.now() });
    const v = document.querySelector<HTMLVideoElement>('[data-testid="replay-video-front"] video')!;
    const look = () => {
      const now = performance.now();
      if (c.crossedAt === undefined && w.__armtwin!.replay.clock.position >= at) c.crossedAt = now;
      if (v.dataset.segmentStart === String(at)) c.shownAt = now;
      else requestAnimationFrame(look);
    };
    requestAnimationFrame(look);
  }, t);

/** That crossing, with when the page's last fetch of segment `name` began and ended (its clock). */
const crossingOf = (page: Page, name: string) =>
  page.evaluate((n) => {
    const fetches = performance
      .getEntriesByType('resource')
      .map((e) => e as PerformanceResourceTiming)
      .filter((e) => e.name.endsWith(`/cameras/front/segments/${encodeURIComponent(n)}`));
    return {
      ...(window as unknown as { __crossing: Crossing }).__crossing,
      fetchStart: fetches.at(-1)?.startTime ?? Infinity,
      fetchedAt: fetches.at(-1)?.responseEnd ?? Infinity,
    };
  }, name);

const replayElbow = (page: Page) =>
  page.evaluate(() => (window as unknown as ReplayHook).__armtwin!.replay.angles[2]!);
const replayPosition = (page: Page) =>
  page.evaluate(() => (window as unknown as ReplayHook).__armtwin!.replay.clock.position);

/** Scrubs to `t` and waits until the paused video shows `t` within one frame. */
async function scrubTo(page: Page, t: number) {
  await page.getByRole('slider', { name: 'Replay position' }).fill(String(t));
  await expect
    .poll(async () => {
      const v = await videoNow(page);
      return { ...v, withinFrame: Math.abs(v.shownMs - t) <= FRAME_MS };
    })
    .toMatchObject({ decoded: true, hidden: false, paused: true, withinFrame: true });
}

test('one timeline: the replay plays the recorded camera with the twin', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  test.setTimeout(120_000);
  const { page } = hud;
  const port = await freePort();
  const camera = await startCamera(stack, arm.id, port);
  await expect
    .poll(async () => (await segments(stack, arm.id)).length, { timeout: 30_000 })
    .toBeGreaterThanOrEqual(1);

  // Home (0°) for a while, then 45° for a while, all on camera.
  await page.waitForTimeout(2000);
  const atHome = Date.now() - 1000;
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('45');
  const want = pwmFromAngle(45, 1);
  await until(() => arm.observer.pwm[2] === want, 10_000, `the sim's elbow at ${want} µs`);
  // long enough that the 2× play below, paused once the video plays, ends before the gap even
  // on a loaded machine (it ended in the gap at load 22 with 2.5 s)
  await page.waitForTimeout(3500);
  const at45 = Date.now() - 1000;

  // The camera server goes away for a few seconds: a gap in the recording.
  await camera.stop();
  const down = Date.now();
  await page.waitForTimeout(4000);
  await startCamera(stack, arm.id, port);
  await expect
    .poll(async () => (await segments(stack, arm.id)).some((s) => s.startMs > down), {
      timeout: 30_000,
    })
    .toBe(true);
  const list = await segments(stack, arm.id);
  const inGap = down + 2000;
  expect(covered(list, atHome) && covered(list, at45)).toBe(true);
  expect(covered(list, inGap)).toBe(false);

  await page.locator('summary', { hasText: 'History' }).click();
  await page.getByRole('tab', { name: 'Replay' }).click();
  await page.getByRole('button', { name: 'Load replay' }).click();
  await expect(page.getByTestId('replay-video-front')).toBeVisible();

  // Paused at T: the video shows T within a frame, the twin the stored pose of T.
  await scrubTo(page, at45);
  expect(await replayElbow(page)).toBeCloseTo(ELBOW_45, 3);
  const sideAt45 = await jpegAt(stack, arm.id, at45);
  await expect.poll(() => jpegNow(page)).toEqual({ frameAt: sideAt45, shown: true });
  await shot(page, testInfo, 'replay-video-45');
  await scrubTo(page, atHome);
  expect(await replayElbow(page)).toBeCloseTo(0, 1);

  // In the gap: no picture, "no recording".
  await page.getByRole('slider', { name: 'Replay position' }).fill(String(inGap));
  await expect(page.getByTestId('replay-video-front')).toContainText('Front: no recording');
  await expect(page.getByTestId('replay-video-side')).toContainText('Side: no recording');
  expect((await videoNow(page)).hidden).toBe(true);
  await shot(page, testInfo, 'replay-video-gap');

  // Played at 2×: the video plays at 2× with the replay; paused, they agree again.
  // from just before the second segment: the boundary comes at once, the gap long after
  const next = list[1]!;
  expect(next.startMs).toBeLessThan(atHome);
  await scrubTo(page, next.startMs - 300);
  await watchCrossing(page, next.startMs);
  await page.getByLabel('Replay speed').selectOption('2');
  await page.getByRole('button', { name: 'Play', exact: true }).click();
  // read together: at a segment boundary (every second at 2×) a new segment loads paused, at rate 1
  await expect
    .poll(async () => {
      const v = await videoNow(page);
      return { paused: v.paused, rate: v.rate };
    })
    .toEqual({ paused: false, rate: 2 });
  // The next segment was fetched while the one before was shown: its last fetch began before Play
  // and had ended when the replay reached it (fetched only at the boundary, as before, it began
  // after Play).
  await expect
    .poll(async () => (await crossingOf(page, next.name)).shownAt !== undefined, {
      timeout: 10_000,
      intervals: [100],
    })
    .toBe(true);
  // paused at once: on a loaded machine each further wait lets the 2× replay run towards the gap
  await page.getByRole('button', { name: 'Pause', exact: true }).click();
  const t = await replayPosition(page);
  const crossing = await crossingOf(page, next.name);
  expect(crossing.fetchStart).toBeLessThan(crossing.armedAt!);
  expect(crossing.fetchedAt).toBeLessThan(crossing.crossedAt!);
  expect(t).toBeGreaterThan(next.startMs);
  await expect
    .poll(async () => {
      const v = await videoNow(page);
      return { paused: v.paused, withinFrame: Math.abs(v.shownMs - t) <= FRAME_MS };
    })
    .toMatchObject({ paused: true, withinFrame: true });

  // The charts (temperature, voltage, power, angle) mark the replay's instant on their time axis.
  await page.getByRole('tab', { name: 'Charts' }).click();
  await expect
    .poll(() =>
      page.evaluate(
        () => (window as unknown as ReplayHook).__armtwin!.history.charts['temp']?.replayAt,
      ),
    )
    .toBe(t);
});
