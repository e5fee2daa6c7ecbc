/**
 * Section `fleet` (issue 34 item 3): N simulated arms at 50 Hz (./lib/fleet-sims.ts: the real
 * simulator, one MQTT connection each, spread over one process per core once one process would
 * be over half busy) through each broker in turn, the bench's Mosquitto and the embedded Aedes
 * broker (`armtwin broker`, what `armtwin up` embeds), into a middleware of its own and InfluxDB,
 * N stepped up (./lib/fleet-steps.ts) until a step loses a point or an arm reports below 95 % of
 * the rate. Per step: every arm's `$TIM` samples as its simulator published them against the
 * servo points InfluxDB holds for it (read back per arm), each arm's achieved rate, and CPU and
 * resident memory of the simulators, the broker and the middleware; the status messages a bare
 * mqtt.js subscriber saw is the broker-side baseline, the 1-arm step the server-side one.
 * Then the page side, same run: the HUD with 1, 10 and 50 arms (./lib/fleet-page.ts, shared
 * with the browser section).
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { findPid, sleep } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import {
  connectMqtt,
  startEmbeddedBroker,
  startMiddleware,
  waitForCount,
  type Middleware,
} from './lib/stack.ts';
import type { BenchContext, Row, Section, SectionOutput } from './lib/types.ts';
import { measureWindow, startFleetSims, storedByArm, type Window } from './lib/fleet-sims.ts';
import {
  BEHIND,
  drainLimitS,
  RATE_HELD,
  highestHeld,
  lossByArm,
  simProcesses,
  spreadAgain,
  stepWhy,
  type ArmPublished,
} from './lib/fleet-steps.ts';
import { fleetPageRows } from './lib/fleet-page.ts';
import { hudPrecheck } from './lib/hud-browser.ts';
import { fleetRows, type FleetStep, type Part } from './lib/fleet-rows.ts';

const RATE_HZ = 50;
const FLUSH_MS = 1000;

const sum = (o: Record<string, number>) => Object.values(o).reduce((a, b) => a + b, 0);

interface Broker {
  name: string;
  tag: string;
  url: string;
  pid: number | undefined;
}

interface Ramp {
  ctx: BenchContext;
  b: Broker;
  mw: Middleware;
  /** Status messages the bare subscriber saw of the step's arms so far. */
  seen: () => number;
  windowS: number;
}

/** One step: `arms` arms in `processes` simulator processes, from start to stored. */
async function runStep(
  r: Ramp,
  arms: number,
  processes: number,
  prefix: string,
): Promise<FleetStep> {
  const { ctx, b, mw, windowS } = r;
  ctx.log(`fleet ${b.name}: ${arms} arms at ${RATE_HZ} Hz in ${processes} process(es)`);
  const before = await mw.metrics();
  const t0 = performance.now();
  const sims = await startFleetSims({
    url: b.url,
    arms,
    processes,
    rateHz: RATE_HZ,
    prefix,
    logDir: ctx.logDir,
  });
  let w: Window;
  let published: Record<string, ArmPublished>;
  try {
    await sleep(1000); // past the first announcements
    w = await measureWindow(
      sims,
      [b.pid ?? -1, mw.child.pid],
      r.seen,
      windowS,
      RATE_HELD * RATE_HZ,
    );
  } finally {
    published = await sims.stop();
  }
  const publishS = (performance.now() - t0) / 1000;
  const stopped = performance.now();
  const want = lossByArm(published, {}).published;
  const stored = () => storedByArm(ctx.influx.url, ctx.influx.db, prefix);
  await waitForCount(async () => sum(await stored()), want, 60_000, 10_000);
  const drainS = (performance.now() - stopped) / 1000;
  const loss = lossByArm(published, await stored());
  const after = await mw.metrics();
  const dropped = (after.points_dropped_total ?? 0) - (before.points_dropped_total ?? 0);
  const limitS = drainLimitS(FLUSH_MS / 1000, publishS);
  const why = stepWhy({
    loss,
    dropped,
    rateHz: RATE_HZ,
    rates: w.rates,
    drainS,
    drainLimitS: limitS,
  });
  const [broker = NaN, middleware = NaN] = w.cpu.slice(-2);
  const [brokerRss = NaN, middlewareRss = NaN] = w.rss.slice(-2);
  const simsPart = (xs: number[]) => xs.slice(0, -2).reduce((a, x) => a + x, 0);
  const r3 = (p: Part, d: number): Part => ({
    sims: round(p.sims, d),
    broker: round(p.broker, d),
    middleware: round(p.middleware, d),
  });
  return {
    arms,
    processes,
    windowS,
    rateHz: {
      min: round(w.rates.min, 1),
      median: round(w.rates.median, 1),
      slowest: w.rates.slowest,
      short: w.rates.short,
    },
    payloadHz: { min: round(w.payloads.min, 1), median: round(w.payloads.median, 1) },
    seenMessages: w.seen,
    publishedMessages: w.publishedMessages,
    middlewareMessages:
      (after['messages_total{topic="status"}'] ?? 0) -
      (before['messages_total{topic="status"}'] ?? 0),
    published: loss.published,
    stored: loss.stored,
    lost: loss.lost,
    extra: loss.extra,
    worstArms: loss.uneven.slice(0, 5),
    dropped,
    drainS: round(drainS, 1),
    drainLimitS: round(limitS, 1),
    cpuShare: r3({ sims: simsPart(w.cpu), broker, middleware }, 3),
    rssMiB: r3({ sims: simsPart(w.rss), broker: brokerRss, middleware: middlewareRss }, 1),
    pass: why === '',
    why,
  };
}

/** One broker's ramp: a middleware of its own, N stepped until a step fails. */
async function ramp(ctx: BenchContext, b: Broker, counts: number[], windowS: number) {
  const mw = await startMiddleware(
    {
      MQTT_URL: b.url,
      MQTT_CLIENT_ID: `bench-fleet-${b.tag}-${process.pid}`,
      INFLUX_URL: ctx.influx.url,
      INFLUX_BUCKET: ctx.influx.bucket,
      SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, `spool-fleet-${b.tag}-`)),
      FLUSH_INTERVAL_MS: String(FLUSH_MS),
      THERMAL_WATCH: 'false',
    },
    path.join(ctx.logDir, `fleet-middleware-${b.tag}.log`),
  );
  const counter = await connectMqtt(b.url, `bench-fleet-count-${b.tag}-${process.pid}`);
  let seen = 0;
  let prefix = '';
  counter.on('message', (topic) => {
    if (topic.startsWith(`arm/${prefix}`)) seen++;
  });
  await counter.subscribeAsync('arm/+/status', { qos: 0 });
  const r: Ramp = { ctx, b, mw, seen: () => seen, windowS };
  const steps: FleetStep[] = [];
  const cores = os.cpus().length;
  let simCost = NaN;
  let behind = false;
  try {
    for (const arms of counts) {
      prefix = `f${b.tag}${arms}-`;
      let step = await runStep(r, arms, simProcesses(arms, simCost, cores, behind), prefix);
      ctx.log(`fleet ${b.name}: ${arms} arms → ${step.why || 'every point stored'}`);
      if (spreadAgain(step, cores)) {
        const first = step;
        prefix = `f${b.tag}${arms}s-`;
        step = await runStep(r, arms, cores, prefix);
        step.firstTry = {
          processes: first.processes,
          rateHz: first.rateHz,
          payloadHz: first.payloadHz,
          why: first.why,
        };
        step.pass = step.why === '';
        ctx.log(
          `fleet ${b.name}: ${arms} arms over ${cores} processes → ${step.why || 'every point stored'}`,
        );
      }
      simCost = (step.cpuShare.sims * 1000) / arms;
      behind = step.payloadHz.median < BEHIND * RATE_HZ;
      steps.push(step);
      if (!step.pass) break;
    }
  } finally {
    await counter.endAsync().catch(() => {});
    await mw.child.stop();
  }
  return { steps, best: highestHeld(steps) };
}

export const fleetSection: Section = {
  id: 'fleet',
  title:
    'Fleet: N simulated arms at 50 Hz through Mosquitto and the embedded broker into the middleware and InfluxDB; the HUD with 1, 10, 50 arms',
  async run(ctx): Promise<SectionOutput> {
    const counts = ctx.quick
      ? [1, 10, 50, 100, 200, 400, 800]
      : [1, 10, 50, 100, 200, 400, 800, 1600, 3200];
    const windowS = ctx.quick ? 5 : 15;
    const mosquitto = await ramp(
      ctx,
      { name: 'Mosquitto', tag: 'm', url: ctx.broker.url, pid: findPid(ctx.broker.confFile) },
      counts,
      windowS,
    );
    const aedes = await startEmbeddedBroker(path.join(ctx.logDir, 'fleet-aedes.log'));
    let embedded;
    try {
      embedded = await ramp(
        ctx,
        { name: 'the embedded broker', tag: 'a', url: aedes.url, pid: aedes.child.pid },
        counts,
        windowS,
      );
    } finally {
      await aedes.child.stop();
    }
    const skipPage = hudPrecheck();
    const page = skipPage ? undefined : await fleetPageRows(ctx);
    const pageRows: Row[] = page
      ? page.rows
      : [
          {
            figure: 'Fleet on the page',
            value: `not run: ${skipPage}`,
            baseline: '—',
            target: '—',
            met: null,
          },
        ];
    return {
      rows: [
        ...fleetRows('Mosquitto', mosquitto.steps, mosquitto.best, RATE_HZ),
        ...fleetRows('the embedded broker', embedded.steps, embedded.best, RATE_HZ),
        ...pageRows,
      ],
      settings: {
        counts,
        windowS,
        rateHz: RATE_HZ,
        flushIntervalMs: FLUSH_MS,
        cores: os.cpus().length,
        brokers: ['mosquitto', 'embedded (armtwin broker, Aedes)'],
        page: page?.settings ?? skipPage,
      },
      data: {
        mosquitto: mosquitto.steps,
        embedded: embedded.steps,
        page: page?.data,
        loadAverage: os.loadavg().map((v) => round(v, 2)),
      },
    };
  },
};
