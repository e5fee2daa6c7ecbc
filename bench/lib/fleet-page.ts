/**
 * The HUD with a fleet (issue 34): `armtwin up --arms arm1:armtwin5,…,armN:armtwin5` (N
 * simulated arms at 50 Hz in one process, its embedded broker), the built HUD (`--hud-dist`)
 * served by the bench and pointed at up's WebSockets, open on arm1 while arm1
 * runs the scripted trajectory, and over a window: the frames the HUD drew, the page's rAF
 * callbacks and its main thread's busy share (CDP TaskDuration). With `profileTo`, a CPU
 * profile of the window is summed by function (self time) into that file: what runs per message.
 */
import fs from 'node:fs';
import mqtt from 'mqtt';
import type { CDPSession } from 'playwright-core';
import { freePorts } from '../../tests/helpers/services.ts';
import { ARMTWIN, startUpProcess } from '../../tests/integration/sim-helpers.ts';
import { cdpMetrics } from './browser-metrics.ts';
import { openHudBrowser } from './hud-browser.ts';
import { sleep } from './proc.ts';
import { serveStatic } from './static.ts';
import { openProbedHud, startProbe, stopProbe } from './probed-hud.ts';
import { SCRIPTED_TRAJECTORY, startTrajectory } from './trajectory.ts';
import { round } from './stats.ts';
import { fmt, type BenchContext, type Row } from './types.ts';

export interface FleetPageFigures {
  arms: number;
  /** Frames the HUD drew per second. */
  drawnFps: number;
  /** The page's requestAnimationFrame callbacks per second (its main thread's smoothness). */
  rafFps: number;
  /** The longest gap between two rAF callbacks, ms. */
  rafMaxGapMs: number;
  /** Main-thread time in tasks ÷ wall time. */
  busy: number;
  /** Messages the page's MQTT clients took in per second (the shown arm's and the fleet's). */
  messagesPerS: number;
  pageErrors: number;
}

interface ProfileNode {
  id: number;
  callFrame: { functionName: string; url: string; lineNumber: number };
  hitCount?: number;
}

/** A CPU profile's self time by function, the heaviest first, one line each. */
function selfTimeLines(
  profile: { nodes: ProfileNode[]; samples: number[]; startTime: number; endTime: number },
  top = 25,
): string[] {
  const total = profile.samples.length || 1;
  const byFn = new Map<string, number>();
  for (const n of profile.nodes) {
    const f = n.callFrame;
    const where = f.url ? `${f.url.split('/').pop()}:${f.lineNumber + 1}` : '(native)';
    const key = `${f.functionName || '(anonymous)'} ${where}`;
    byFn.set(key, (byFn.get(key) ?? 0) + (n.hitCount ?? 0));
  }
  const ms = (profile.endTime - profile.startTime) / 1000;
  return [...byFn]
    .sort((a, b) => b[1] - a[1])
    .slice(0, top)
    .map(
      ([k, hits]) =>
        `${((100 * hits) / total).toFixed(1)}%  ${((ms * hits) / total).toFixed(0)} ms  ${k}`,
    );
}

const fleetMessages = (page: import('playwright-core').Page) =>
  page.evaluate(() => {
    const w = window as unknown as {
      __armtwin: {
        store: { counters: { messages: number } };
        robots: { fleet: { counters: { messages: number } } };
      };
    };
    return w.__armtwin.store.counters.messages + w.__armtwin.robots.fleet.counters.messages;
  });

async function profiled<T>(cdp: CDPSession, file: string | undefined, run: () => Promise<T>) {
  if (!file) return run();
  await cdp.send('Profiler.enable');
  await cdp.send('Profiler.setSamplingInterval', { interval: 500 });
  await cdp.send('Profiler.start');
  const out = await run();
  const { profile } = (await cdp.send('Profiler.stop')) as {
    profile: Parameters<typeof selfTimeLines>[0];
  };
  fs.writeFileSync(file, `${selfTimeLines(profile).join('\n')}\n`);
  return out;
}

export async function measureFleetPage(
  arms: number,
  windowS: number,
  o: {
    /** The built HUD to serve (`--hud-dist`: an older build, for a before/after). */
    hudDist: string;
    chromiumArgs?: readonly string[];
    log(line: string): void;
    profileTo?: string;
  },
): Promise<FleetPageFigures> {
  const [httpPort = 0, mqttPort = 0] = await freePorts(2);
  const list = Array.from({ length: arms }, (_, i) => `arm${i + 1}:armtwin5`).join(',');
  o.log(`fleet page: armtwin up with ${arms} arm(s)`);
  const up = await startUpProcess(
    [ARMTWIN, 'up'],
    ['--no-middleware', '--no-web', '--arms', list],
    { httpPort, mqttPort },
  );
  const web = await serveStatic(o.hudDist);
  const client = await mqtt.connectAsync(`mqtt://127.0.0.1:${mqttPort}`);
  const { browser, page, cdp, pageErrors } = await openHudBrowser(o.chromiumArgs);
  let stopTrajectory = () => {};
  try {
    const broker = encodeURIComponent(`ws://127.0.0.1:${httpPort}/mqtt`);
    await openProbedHud(page, `${web.url}?broker=${broker}&arm=arm1`, 50, windowS * 240);
    stopTrajectory = startTrajectory(client, 'arm1', SCRIPTED_TRAJECTORY);
    await sleep(2000); // settle (the fleet list filled, the resolution governor, JIT)
    const n0 = await fleetMessages(page);
    const m0 = await cdpMetrics(cdp);
    await startProbe(page);
    const probe = await profiled(cdp, o.profileTo, async () => {
      await sleep(windowS * 1000);
      return stopProbe(page);
    });
    const m1 = await cdpMetrics(cdp);
    const n1 = await fleetMessages(page);
    const s = probe.windowMs / 1000;
    return {
      arms,
      drawnFps: probe.frames / s,
      rafFps: probe.rafCount / s,
      rafMaxGapMs: probe.rafMaxGapMs,
      busy: (m1.task - m0.task) / ((m1.at - m0.at) / 1000),
      messagesPerS: (n1 - n0) / ((m1.at - m0.at) / 1000),
      pageErrors: pageErrors.length,
    };
  } finally {
    stopTrajectory();
    await browser.close().catch(() => {});
    await client.endAsync().catch(() => {});
    await web.close();
    await up.stop();
  }
}

/** The fleet sizes the browser section measures, the first the baseline. */
export const FLEET_SIZES = [1, 10, 50] as const;

/**
 * The browser section's fleet rows (BENCHMARKS.md §4, "A fleet on the page"): the HUD's frames
 * and main-thread busy share with 1, 10 and 50 arms in the fleet, one after the other in the
 * same run, the 1-arm run the baseline.
 */
export async function fleetPageRows(
  ctx: Pick<BenchContext, 'quick' | 'chromiumArgs' | 'log' | 'hudDist'>,
): Promise<{ rows: Row[]; settings: Record<string, unknown>; data: Record<string, unknown> }> {
  const windowS = ctx.quick ? 8 : 20;
  const runs: FleetPageFigures[] = [];
  for (const n of FLEET_SIZES)
    runs.push(
      await measureFleetPage(n, windowS, {
        hudDist: ctx.hudDist,
        chromiumArgs: ctx.chromiumArgs,
        log: ctx.log,
      }),
    );
  const [one, , most] = runs as [FleetPageFigures, FleetPageFigures, FleetPageFigures];
  const each = (f: (r: FleetPageFigures) => string) => runs.map(f).join(' / ');
  const sizes = FLEET_SIZES.join(' / ');
  const rows: Row[] = [
    {
      figure: `Fleet on the page, arm1 shown: rAF callbacks/s with ${sizes} arms`,
      value: each((r) => fmt(r.rafFps, 1)),
      baseline: `1 arm ${fmt(one.rafFps, 1)}; issue 34 before: 9.8 frames/s with 50 arms, 60.2 with 1`,
      target: `${FLEET_SIZES.at(-1)} arms ≥ 0.9 × 1 arm`,
      met: most.rafFps >= 0.9 * one.rafFps,
    },
    {
      figure: `Fleet on the page: main-thread busy share with ${sizes} arms`,
      value: each((r) => `${fmt(r.busy * 100, 1)} %`),
      baseline: `1 arm ${fmt(one.busy * 100, 1)} %`,
      target: 'reported',
      met: null,
    },
    {
      figure: `Fleet on the page: frames drawn/s; MQTT messages into the page/s, with ${sizes} arms`,
      value: `${each((r) => fmt(r.drawnFps, 1))}; ${each((r) => fmt(r.messagesPerS, 0))}`,
      baseline: `1 arm ${fmt(one.drawnFps, 1)}; ${fmt(one.messagesPerS, 0)}`,
      target: 'reported',
      met: null,
    },
  ];
  return {
    rows,
    settings: {
      fleetSizes: FLEET_SIZES,
      windowS,
      how: 'armtwin up --no-middleware --arms arm1:armtwin5,… (50 Hz each, embedded broker); the HUD (--hud-dist) on arm1 through up’s /mqtt; the scripted trajectory on arm1',
    },
    data: {
      runs: runs.map((r) => ({
        ...r,
        drawnFps: round(r.drawnFps, 2),
        rafFps: round(r.rafFps, 2),
        busy: round(r.busy, 4),
        messagesPerS: round(r.messagesPerS, 1),
      })),
    },
  };
}
