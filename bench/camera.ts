/**
 * Section 7: cameras (issue 15). ffmpeg's test source at 640×480, 30 frames/s, carries the wall
 * clock at which ffmpeg made each frame as a stripe of black and white blocks
 * (packages/camera/src/time-stripe.ts). Each stream is served by its own `armtwin camera
 * --kinds <kind> --no-announce` (a child: node + its ffmpeg) on 127.0.0.1; the bench announces
 * it on MQTT with the one kind it measures, so the HUD plays that path: `mjpeg` (fetch +
 * createImageBitmap → canvas) or `h264-ws` (WebSocket → WebCodecs → canvas). The built HUD runs
 * in headless Chromium on http://127.0.0.1 (a secure context: WebCodecs exists), with the
 * simulated arm moving through a scripted trajectory, so the 3D view renders every frame; the
 * announced cameras have a pose, so each is also a screen in the 3D view.
 *
 * Glass to glass: ./lib/camera-probe.ts reads the stripe from the canvas each camera view
 * displays, in a requestAnimationFrame callback, and subtracts it from `Date.now()` on the same
 * machine, at the first page frame that shows each camera frame; it also keeps the age of the
 * picture shown at every page frame (a held or frozen picture keeps ageing). The method and its
 * limits are described there.
 *
 * Windows, in turn, in one page: no camera (baseline), one and two MJPEG cameras, one and two
 * H.264 cameras, all while the arm moves; then, with the arm still and a camera without a pose
 * (no 3D screen, so the 3D view does not redraw), one camera of each path: how much of the
 * latency is the page's own load. Per window: latency and picture age per camera, camera frames
 * shown per second, the page's rAF rate and 3D frames rendered, main-thread busy share (CDP
 * `Performance.getMetrics` TaskDuration, as ./browser.ts), long tasks, the probe's own
 * pixel-reading time, and the CPU of each camera server (node + ffmpeg, utime + stime from
 * /proc over the window).
 */
import fs from 'node:fs';
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import type { CDPSession, Page } from 'playwright-core';
import type { CameraKind } from '@armtwin/camera/announcement';
import { connectMqtt, startSim } from './lib/stack.ts';
import { sleep, until } from './lib/proc.ts';
import { serveStatic } from './lib/static.ts';
import { installCameraProbe, type CameraProbeResult } from './lib/camera-probe.ts';
import { startCameraServer, treeMeter, type CameraServer } from './lib/camera-server.ts';
import {
  ANCHORS,
  cameraRows,
  KINDS,
  latencySvg,
  TARGET,
  windowsJson,
  type CameraWindow,
} from './lib/camera-report.ts';
import { summarize } from './lib/stats.ts';
import type { BenchContext, Section, SectionOutput } from './lib/types.ts';
import { startTrajectory, type Trajectory } from './lib/trajectory.ts';
import { HUD_DIST, hudPrecheck, hudReady, openHudBrowser } from './lib/hud-browser.ts';
import { cdpMetrics, webglRendererName } from './lib/browser-metrics.ts';

const ARM = 'bench-cam';
const DIST = HUD_DIST;
const FFMPEG = '/usr/bin/ffmpeg';
const WIDTH = 640;
const HEIGHT = 480;
const FPS = 30;
/** Two poses of the demo arm (µs, servos 000–005), alternated so the 3D view keeps rendering. */
const POSES = [
  [1500, 1300, 1700, 1500, 1500, 1500],
  [1800, 1600, 1400, 1700, 1650, 1800],
];
const MOVE_MS = 1000;
const TRAJECTORY: Trajectory = { poses: POSES, moveMs: MOVE_MS, stepMs: 1500 };

/** One measurement window with `count` cameras of `kind` (0: the 3D view alone). */
async function runWindow(
  ctx: BenchContext,
  page: Page,
  cdp: CDPSession,
  client: MqttClient,
  kind: CameraKind | null,
  count: number,
  windowS: number,
  /** Posed cameras are also screens in the 3D view; unposed ones are in the panel only. */
  posed = true,
): Promise<CameraWindow> {
  const tag = `${kind === 'h264-ws' ? 'h264' : (kind ?? 'none')}${posed ? '' : '-still'}`;
  const servers: CameraServer[] = [];
  const announce = (camId: string, body: object | '') =>
    client.publishAsync(`arm/${ARM}/camera/${camId}`, body === '' ? '' : JSON.stringify(body), {
      qos: 1,
      retain: true,
    });
  try {
    for (let i = 0; i < count && kind; i++) {
      const camId = `${tag}-${count}-${i + 1}`;
      const s = await startCameraServer({
        armId: ARM,
        kind,
        camId,
        label: `Bench ${tag} ${count}-${i + 1}`,
        width: WIDTH,
        height: HEIGHT,
        fps: FPS,
        logFile: path.join(ctx.logDir, `camera-${camId}.log`),
      });
      servers.push(s);
      await announce(camId, {
        url: s.url,
        kind,
        label: s.label,
        ...(posed
          ? { pose: { position: [450 - 900 * i, -400, 350], lookAt: [0, 0, 150] }, fovDeg: 50 }
          : {}),
      });
    }
    const labels = servers.map((s) => s.label);
    // Each view is up and drawing (its age line says "last frame … ago"), then 2 s to settle.
    const live = await until(
      () =>
        page.evaluate(
          (ls) =>
            ls.every((l) =>
              /last frame/.test(
                document
                  .querySelector(`section[aria-label="${CSS.escape(`Camera ${l}`)}"]`)
                  ?.querySelector('[data-testid="camera-age"]')?.textContent ?? '',
              ),
            ),
          labels,
        ),
      30_000,
      250,
    );
    if (!live) throw new Error(`${kind} × ${count}: a camera view never drew a frame`);
    await sleep(2000);
    ctx.log(
      `camera: ${count} × ${kind ?? 'no camera'}${posed ? '' : ', 3D view still'}, ${windowS} s`,
    );
    const meters = servers.map((s) => treeMeter(s.child.pid));
    const m0 = await cdpMetrics(cdp);
    for (const m of meters) m.start();
    await page.evaluate(
      (ls) =>
        (window as unknown as { __cameraProbe: { start(l: string[]): void } }).__cameraProbe.start(
          ls,
        ),
      labels,
    );
    await sleep(windowS * 1000);
    const p = await page.evaluate(() =>
      (window as unknown as { __cameraProbe: { stop(): CameraProbeResult } }).__cameraProbe.stop(),
    );
    const server = meters.map((m) => m.stop());
    const m1 = await cdpMetrics(cdp);
    const wallS = (m1.at - m0.at) / 1000;
    const all = p.cameras.flatMap((c) => c.latency);
    return {
      kind,
      cameras: count,
      fps: p.rafCount / (p.windowMs / 1000),
      renderedPerS: p.renderedFramesDelta / (p.windowMs / 1000),
      busy: (m1.task - m0.task) / wallS,
      scriptShare: (m1.script - m0.script) / wallS,
      readerShare: p.readerMsTotal / p.windowMs,
      readerMaxMs: p.readerMsMax,
      longTasks: p.longTasks.length,
      longestTaskMs: Math.max(0, ...p.longTasks.map((t) => t.duration)),
      rafMaxGapMs: p.rafMaxGapMs,
      latency: summarize(all),
      age: summarize(p.cameras.flatMap((c) => c.age)),
      perCamera: p.cameras.map((c) => ({
        ...c,
        latency: summarize(c.latency),
        age: summarize(c.age),
        shownPerS: c.distinct / (p.windowMs / 1000),
      })),
      server,
      raw: all,
    };
  } finally {
    for (const s of servers) await announce(s.camId, '').catch(() => {});
    for (const s of servers) await s.child.stop();
  }
}

export const cameraSection: Section = {
  id: 'camera',
  title: 'Cameras: glass to glass (MJPEG, H.264/WebCodecs), server CPU, page load',
  precheck() {
    if (!fs.existsSync(FFMPEG)) return `${FFMPEG} not found (apt install ffmpeg)`;
    return hudPrecheck();
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const windowS = ctx.quick ? 6 : 12;
    const web = await serveStatic(DIST);
    const sim = await startSim(ctx.broker.url, ARM, 50, path.join(ctx.logDir, 'camera-sim.log'));
    const client = await connectMqtt(ctx.broker.url, `bench-cam-${process.pid}`);
    const { browser, page, cdp, pageErrors } = await openHudBrowser(ctx.chromiumArgs);
    let stopTrajectory = () => {};
    try {
      await page.goto(`${web.url}?broker=${encodeURIComponent(ctx.broker.wsUrl)}&arm=${ARM}`);
      await hudReady(page);
      const secure = await page.evaluate(() => typeof VideoDecoder === 'function');
      if (!secure) throw new Error('no VideoDecoder in the page (not a secure context?)');
      const args = { width: WIDTH, height: HEIGHT, maxSamples: windowS * 90 };
      if (!(await page.evaluate(installCameraProbe, args)))
        throw new Error('window.__armtwin has no timeStripe/viewer (HUD built before the hook?)');

      stopTrajectory = startTrajectory(client, ARM, TRAJECTORY);

      const w: Record<string, CameraWindow> = {};
      w.none = await runWindow(ctx, page, cdp, client, null, 0, windowS);
      for (const kind of KINDS)
        for (const n of [1, 2])
          w[`${kind}-${n}`] = await runWindow(ctx, page, cdp, client, kind, n, windowS);
      // Baseline for the page's share of the latency: the arm stands still and the camera has
      // no pose (no screen), so the 3D view does not redraw; the camera plays in the panel only.
      stopTrajectory();
      await sleep(MOVE_MS + 500);
      for (const kind of KINDS)
        w[`${kind}-still`] = await runWindow(ctx, page, cdp, client, kind, 1, windowS, false);

      const file = `${ctx.stamp}-camera-latency.svg`;
      fs.writeFileSync(
        path.join(ctx.resultsDir, file),
        latencySvg(
          w,
          `Camera glass to glass (stripe → page frame), ${WIDTH}×${HEIGHT} @ ${FPS} fps, one camera, ${windowS} s per series`,
        ),
      );
      const webgl = await webglRendererName(page);
      return {
        rows: cameraRows(w),
        plots: [{ file, title: 'Camera glass to glass' }],
        settings: {
          size: `${WIDTH}x${HEIGHT}`,
          fps: FPS,
          windowS,
          viewport: '1280x800',
          chromiumArgs: ctx.chromiumArgs,
          simRateHz: 50,
          trajectory: TRAJECTORY,
          server: 'one `armtwin camera --source testsrc --kinds <kind> --no-announce` per stream',
          target: TARGET,
          anchors: ANCHORS,
          method:
            'stripe (ffmpeg RTCTIME) read from the displayed canvas in a rAF callback; Date.now() − stamp at the first page frame showing each camera frame',
        },
        data: {
          windows: windowsJson(w),
          webglRenderer: webgl,
          pageErrors: pageErrors.slice(0, 10),
        },
      };
    } finally {
      stopTrajectory();
      await browser.close().catch(() => {});
      await client.endAsync().catch(() => {});
      await sim.stop();
      await web.close();
    }
  },
};
