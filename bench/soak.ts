/**
 * Soak (issue 17 item 6): the HUD left open for a long session. `armtwin sim --rate 250` moving
 * through a scripted trajectory, the middleware storing it in a throwaway influxd, the built HUD
 * served as `npm start` serves it (`/api/*` proxied to the middleware), in headless Chromium with
 * the Health panel's strip charts running, the History panel open (loaded from storage) and,
 * when ffmpeg is there, one MJPEG test-source camera on screen. Every minute: a forced garbage
 * collection (CDP `HeapProfiler.collectGarbage`), then the JS heap in use
 * (`Runtime.getHeapUsage`) and the DOM counters (`Memory.getDOMCounters`: nodes, listeners).
 * The figures are the least-squares slopes over minutes ≥ 2 (the first minutes fill the fixed
 * rings and warm the JIT): MiB per 10 minutes and DOM nodes per 10 minutes. A heap snapshot at
 * minute 2 and at the end, summed by constructor, names what grew (./lib/heap-snapshot.ts).
 * Not in the default run (it takes `--soak-minutes`, default 30): `npm run bench -- --only soak`.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { connectMqtt, startMiddleware, startSim } from './lib/stack.ts';
import { sleep, until } from './lib/proc.ts';
import { serveStatic } from '../tests/e2e/support/static-server.ts';
import { startCameraServer, type CameraServer } from './lib/camera-server.ts';
import { heapGrowth, heapSummary, type HeapSummary } from './lib/heap-snapshot.ts';
import { slopeFrom } from './lib/slope.ts';
import { round } from './lib/stats.ts';
import { barChartSvg } from './lib/svg.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';
import { startTrajectory, type Trajectory } from './lib/trajectory.ts';
import { hudPrecheck, openHudBrowser, openLiveHud } from './lib/hud-browser.ts';

const ARM = 'bench-soak';
const FFMPEG = '/usr/bin/ffmpeg';
const MIB = 1024 * 1024;
/** Minutes before this one are warm-up, left out of the slopes. */
const FIT_FROM_MIN = 2;
/** Targets (issue 17): heap growth below 1 MiB per 10 min; DOM nodes flat. */
const HEAP_TARGET_MIB_PER_10MIN = 1;
const DOM_TARGET_PER_10MIN = 10;
const TRAJECTORY: Trajectory = {
  poses: [
    [1500, 1500, 1500, 1500, 1500, 1500],
    [1900, 1300, 1200, 1700, 1650, 1800],
    [1100, 1700, 1800, 1300, 1350, 1600],
  ],
  moveMs: 1000,
  stepMs: 1500,
};

export interface SoakSample {
  minute: number;
  heapMiB: number;
  heapTotalMiB: number;
  domNodes: number;
  listeners: number;
  documents: number;
  messages: number;
}

export const soakSection: Section = {
  id: 'soak',
  title: 'Soak: the HUD open for a long session at 250 Hz (heap and DOM per minute)',
  precheck() {
    return hudPrecheck();
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const minutes = ctx.soakMinutes;
    const dist = ctx.hudDist;
    if (!fs.existsSync(path.join(dist, 'index.html'))) throw new Error(`${dist}: no index.html`);
    const spool = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-soak-spool-'));
    const mw = await startMiddleware(
      {
        MQTT_URL: ctx.broker.url,
        MQTT_CLIENT_ID: `bench-soak-mw-${process.pid}`,
        INFLUX_URL: ctx.influx.url,
        INFLUX_BUCKET: ctx.influx.bucket,
        SPOOL_DIR: spool,
      },
      path.join(ctx.logDir, 'soak-middleware.log'),
    );
    const web = await serveStatic(dist, {
      proxy: { prefix: '/api/', target: `http://127.0.0.1:${mw.port}` },
    });
    const sim = await startSim(ctx.broker.url, ARM, 250, path.join(ctx.logDir, 'soak-sim.log'));
    const client = await connectMqtt(ctx.broker.url, `bench-soak-${process.pid}`);
    let camera: CameraServer | undefined;
    let stopTrajectory = () => {};
    const { browser, page, cdp, pageErrors } = await openHudBrowser(ctx.chromiumArgs);
    try {
      stopTrajectory = startTrajectory(client, ARM, TRAJECTORY);
      if (fs.existsSync(FFMPEG) && !ctx.quick) {
        camera = await startCameraServer({
          armId: ARM,
          kind: 'mjpeg',
          camId: 'soak-1',
          label: 'Soak camera',
          width: 640,
          height: 480,
          fps: 15,
          logFile: path.join(ctx.logDir, 'soak-camera.log'),
        });
        await client.publishAsync(
          `arm/${ARM}/camera/${camera.camId}`,
          JSON.stringify({
            url: camera.url,
            kind: 'mjpeg',
            label: camera.label,
            pose: { position: [450, -400, 350], lookAt: [0, 0, 150] },
            fovDeg: 50,
          }),
          { qos: 1, retain: true },
        );
      }
      const url = `${web.url}?broker=${encodeURIComponent(ctx.broker.wsUrl)}&arm=${ARM}`;
      ctx.log(`soak: HUD at ${url}`);
      await openLiveHud(page, url, 100);
      // Let the middleware store a few seconds, then open History (it loads the last 5 min).
      await sleep(3000);
      await page.locator('details.history > summary').click();
      const historyLoaded = await until(
        () =>
          page.evaluate(
            () =>
              document.querySelector('details.history')?.hasAttribute('open') === true &&
              !/Loading…|Nothing loaded yet/.test(
                document.querySelector('details.history')?.textContent ?? '',
              ),
          ),
        60_000,
        500,
      );
      const cameraShown = camera
        ? await until(
            () =>
              page.evaluate(
                (l) =>
                  /last frame/.test(
                    document
                      .querySelector(`section[aria-label="${CSS.escape(`Camera ${l}`)}"]`)
                      ?.querySelector('[data-testid="camera-age"]')?.textContent ?? '',
                  ),
                camera!.label,
              ),
            30_000,
            500,
          )
        : false;
      const chartCanvases = await page.evaluate(
        () => document.querySelectorAll('.uplot canvas').length,
      );
      ctx.log(
        `soak: ${minutes} min; history ${historyLoaded ? 'loaded' : 'NOT loaded'}, camera ${camera ? (cameraShown ? 'shown' : 'NOT shown') : 'none'}, ${chartCanvases} chart canvases`,
      );

      const t0 = performance.now();
      const samples: SoakSample[] = [];
      let early: HeapSummary | null = null;
      const sample = async (minute: number) => {
        await cdp.send('HeapProfiler.collectGarbage');
        const heap = (await cdp.send('Runtime.getHeapUsage')) as {
          usedSize: number;
          totalSize: number;
        };
        const dom = (await cdp.send('Memory.getDOMCounters')) as {
          documents: number;
          nodes: number;
          jsEventListeners: number;
        };
        const messages = await page.evaluate(
          () =>
            (window as unknown as { __armtwin: { store: { counters: { messages: number } } } })
              .__armtwin.store.counters.messages,
        );
        const s: SoakSample = {
          minute,
          heapMiB: round(heap.usedSize / MIB, 3),
          heapTotalMiB: round(heap.totalSize / MIB, 3),
          domNodes: dom.nodes,
          listeners: dom.jsEventListeners,
          documents: dom.documents,
          messages,
        };
        samples.push(s);
        ctx.log(
          `soak: min ${minute}: heap ${fmt(s.heapMiB, 2)} MiB, ${s.domNodes} DOM nodes, ${s.listeners} listeners, ${messages} messages`,
        );
      };
      for (let m = 0; m <= minutes; m++) {
        const due = t0 + m * 60_000;
        await sleep(Math.max(0, due - performance.now()));
        await sample(m);
        if (m === FIT_FROM_MIN && minutes > FIT_FROM_MIN) early = await heapSummary(cdp);
      }
      const late = early ? await heapSummary(cdp) : null;
      const grew = early && late ? heapGrowth(early, late, 20) : [];
      stopTrajectory();

      const xs = samples.map((s) => s.minute);
      const heapFit = slopeFrom(
        xs,
        samples.map((s) => s.heapMiB),
        FIT_FROM_MIN,
      );
      const domFit = slopeFrom(
        xs,
        samples.map((s) => s.domNodes),
        FIT_FROM_MIN,
      );
      const listenerFit = slopeFrom(
        xs,
        samples.map((s) => s.listeners),
        FIT_FROM_MIN,
      );
      const heapPer10 = heapFit.slope * 10;
      const domPer10 = domFit.slope * 10;
      const first = samples.find((s) => s.minute === FIT_FROM_MIN) ?? samples[0]!;
      const last = samples[samples.length - 1]!;
      const rows: Row[] = [
        {
          figure: `JS heap after GC, slope over minutes ${FIT_FROM_MIN}–${last.minute} (MiB per 10 min)`,
          value: `${fmt(heapPer10, 3)} (${fmt(first.heapMiB, 2)} → ${fmt(last.heapMiB, 2)} MiB)`,
          baseline:
            'before the fix: 2.15 MiB per 10 min (run 2026-11-24T15-13-21, 6 min at 250 Hz, --hud-dist of the unfixed build); issue 17: ≈ 3 at 50 Hz over 12 min',
          target: `< ${HEAP_TARGET_MIB_PER_10MIN} MiB per 10 min`,
          met: heapPer10 < HEAP_TARGET_MIB_PER_10MIN,
        },
        {
          figure: 'DOM nodes, slope (per 10 min); event listeners',
          value: `${fmt(domPer10, 1)} (${first.domNodes} → ${last.domNodes}); listeners ${first.listeners} → ${last.listeners}`,
          baseline: 'flat',
          target: `flat (|slope| ≤ ${DOM_TARGET_PER_10MIN} per 10 min)`,
          met: Math.abs(domPer10) <= DOM_TARGET_PER_10MIN,
        },
      ];
      const file = `${ctx.stamp}-soak-heap.svg`;
      fs.writeFileSync(
        path.join(ctx.resultsDir, file),
        barChartSvg({
          title: `HUD soak at 250 Hz: JS heap after GC, ${minutes} min`,
          xLabel: 'minute',
          yLabel: 'MiB',
          categories: xs.map(String),
          labelEvery: minutes > 12 ? 5 : 1,
          series: [
            { name: 'JS heap in use', values: samples.map((s) => s.heapMiB), colour: '#d95f02' },
          ],
        }),
      );
      return {
        rows,
        plots: [{ file, title: 'Soak: JS heap per minute' }],
        settings: {
          minutes,
          simRateHz: 250,
          servos: 6,
          fitFromMinute: FIT_FROM_MIN,
          panels: ['Health (strip charts)', 'History (charts, last 5 min)'],
          camera: camera ? 'mjpeg 640×480 15 fps testsrc, posed' : 'none',
          hudDist: path.relative(process.cwd(), dist) || dist,
          viewport: '1280x800',
          chromiumArgs: ctx.chromiumArgs,
          trajectory: TRAJECTORY,
        },
        data: {
          samples,
          heapSlopeMiBPer10Min: round(heapPer10, 4),
          domNodesSlopePer10Min: round(domPer10, 2),
          listenersSlopePer10Min: round(listenerFit.slope * 10, 2),
          fitPoints: heapFit.n,
          historyLoaded,
          cameraShown,
          chartCanvases,
          heapGrowthByConstructor: grew.map((g) => ({
            ...g,
            kib: round(g.bytes / 1024, 1),
          })),
          pageErrors: pageErrors.slice(0, 10),
        },
      };
    } finally {
      stopTrajectory();
      await browser.close().catch(() => {});
      if (camera) {
        await client
          .publishAsync(`arm/${ARM}/camera/${camera.camId}`, '', { qos: 1, retain: true })
          .catch(() => {});
        await camera.child.stop();
      }
      await client.endAsync().catch(() => {});
      await sim.stop();
      await web.close();
      await mw.child.stop();
      fs.rmSync(spool, { recursive: true, force: true });
    }
  },
};
