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
import { cpuMeter, findPid, sleep } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { connectMqtt, startEmbeddedBroker, startMiddleware, waitForCount } from './lib/stack.ts';
import type { BenchContext, Row, Section, SectionOutput } from './lib/types.ts';
import { startFleetSims, windowRates } from './lib/fleet-sims.ts';
import {
  highestHeld,
  lossByArm,
  rateSummary,
  simProcesses,
  stepWhy,
  type LossAccount,
  type RateSummary,
} from './lib/fleet-steps.ts';
import { fleetPageRows } from './lib/fleet-page.ts';
import { hudPrecheck } from './lib/hud-browser.ts';
import { fleetRows, type FleetStep, type Part } from './lib/fleet-rows.ts';

const RATE_HZ = 50;
const FLUSH_MS = 1000;

/** Resident memory of a process, MiB (NaN once it is gone). */
function rssMiB(pid: number | undefined): number {
  if (!pid) return NaN;
  try {
    const m = /VmRSS:\s+(\d+) kB/.exec(fs.readFileSync(`/proc/${pid}/status`, 'utf8'));
    return m ? Number(m[1]) / 1024 : NaN;
  } catch {
    return NaN;
  }
}

/** Servo points (angles and temperatures) InfluxDB holds per arm for arms named `prefix…`. */
async function storedByArm(url: string, db: string, prefix: string) {
  const q = `SELECT count("angle"), count("temp") FROM "servo" WHERE "arm" =~ /^${prefix}/ GROUP BY "arm"`;
  const res = await fetch(`${url}/query?db=${encodeURIComponent(db)}`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  }).catch(() => null);
  const out: Record<string, number> = {};
  if (!res?.ok) return out;
  const body = (await res.json()) as {
    results?: { series?: { tags?: { arm?: string }; values: unknown[][] }[] }[];
  };
  for (const s of body.results?.[0]?.series ?? []) {
    const v = s.values[0] ?? [];
    if (s.tags?.arm) out[s.tags.arm] = Number(v[1] ?? 0) + Number(v[2] ?? 0);
  }
  return out;
}

const sum = (o: Record<string, number>) => Object.values(o).reduce((a, b) => a + b, 0);

interface Broker {
  name: string;
  tag: string;
  url: string;
  pid: number | undefined;
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
  const steps: FleetStep[] = [];
  const cores = os.cpus().length;
  let simCost = NaN;
  try {
    for (const arms of counts) {
      prefix = `f${b.tag}${arms}-`;
      const processes = simProcesses(arms, simCost, cores);
      ctx.log(`fleet ${b.name}: ${arms} arms at ${RATE_HZ} Hz in ${processes} process(es)`);
      const before = await mw.metrics();
      const sims = await startFleetSims({
        url: b.url,
        arms,
        processes,
        rateHz: RATE_HZ,
        prefix,
        logDir: ctx.logDir,
      });
      let rates: RateSummary;
      let cpu: Part;
      let rss: Part;
      let seenInWindow: number;
      let published;
      try {
        await sleep(1000); // past the first announcements
        const meters = [...sims.pids, b.pid ?? -1, mw.child.pid].map((p) => cpuMeter(p));
        for (const m of meters) m.start();
        const seen0 = seen;
        const snap0 = await sims.snapshot();
        await sleep(windowS * 1000);
        const snap1 = await sims.snapshot();
        const shares = meters.map((m) => m.stop().share);
        seenInWindow = seen - seen0;
        rates = rateSummary(windowRates(snap0, snap1));
        const simShares = shares.slice(0, sims.pids.length);
        cpu = {
          sims: simShares.reduce((a, s) => a + s, 0),
          broker: shares.at(-2)!,
          middleware: shares.at(-1)!,
        };
        rss = {
          sims: sims.pids.reduce((a, p) => a + rssMiB(p), 0),
          broker: rssMiB(b.pid),
          middleware: rssMiB(mw.child.pid),
        };
      } finally {
        published = await sims.stop();
      }
      await sleep(FLUSH_MS + 500);
      const after = await mw.metrics();
      const dropped = (after.points_dropped_total ?? 0) - (before.points_dropped_total ?? 0);
      const want = lossByArm(published, {}).published;
      const { got } = await waitForCount(
        async () => sum(await storedByArm(ctx.influx.url, ctx.influx.db, prefix)),
        want,
        30_000,
        5000,
      );
      const loss: LossAccount = lossByArm(
        published,
        await storedByArm(ctx.influx.url, ctx.influx.db, prefix),
      );
      const why = stepWhy({ loss, dropped, rateHz: RATE_HZ, rates });
      simCost = (cpu.sims * 1000) / arms;
      steps.push({
        arms,
        processes,
        windowS,
        rateHz: { min: round(rates.min, 1), median: round(rates.median, 1) },
        seenMessages: seenInWindow,
        middlewareMessages:
          (after['messages_total{topic="status"}'] ?? 0) -
          (before['messages_total{topic="status"}'] ?? 0),
        published: loss.published,
        stored: got,
        lost: loss.lost,
        extra: loss.extra,
        worstArms: loss.uneven.slice(0, 5),
        dropped,
        cpuShare: { sims: round(cpu.sims, 3), broker: round(cpu.broker, 3), middleware: round(cpu.middleware, 3) },
        rssMiB: { sims: round(rss.sims, 1), broker: round(rss.broker, 1), middleware: round(rss.middleware, 1) },
        pass: why === '',
        why,
      });
      ctx.log(`fleet ${b.name}: ${arms} arms → ${why || 'every point stored'}`);
      if (why) break;
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
    const counts = ctx.quick ? [1, 10, 50, 100, 200, 400] : [1, 10, 50, 100, 200, 400, 800, 1600];
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
      : [{ figure: 'Fleet on the page', value: `not run: ${skipPage}`, baseline: '—', target: '—', met: null }];
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
