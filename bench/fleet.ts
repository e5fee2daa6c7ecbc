/**
 * Section `fleet` (issue 34 item 3, server side; a skeleton): N simulated arms in one process
 * (./agents/fleet.ts: the real simulator, one MQTT connection each, status at 50 Hz) through
 * the bench's Mosquitto into the middleware (defaults) and InfluxDB, N stepped up until a step
 * loses something or the simulators cannot hold the rate. Per step: CPU (share of a core) and
 * resident memory of the simulators' process, the broker and the middleware, each also per arm;
 * the status messages a bare mqtt.js subscriber saw (the baseline: what the broker delivered)
 * against what the middleware took in, and the points it made against those InfluxDB holds (servo, profile and audit points).
 * Not yet here: the embedded broker's run, the page side (HUD frame rate with 1/10/50 arms).
 */
import fs from 'node:fs';
import path from 'node:path';
import { cpuMeter, findPid, sleep } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import {
  agentResult,
  connectMqtt,
  firstRow,
  startAgent,
  startMiddleware,
  waitForCount,
} from './lib/stack.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const RATE_HZ = 50;
const FLUSH_MS = 1000;
/**
 * The share of the rate the simulators must hold for a step to count (they share the cores with
 * the broker, the middleware and influxd: on a loaded machine a lone sim keeps about 87 %).
 */
const SIM_HELD = 0.8;

interface FleetStep {
  arms: number;
  windowS: number;
  /** Status messages per arm per second, as the bare subscriber saw them. */
  perArmHz: number;
  seenMessages: number;
  middlewareMessages: number;
  producedPoints: number;
  storedPoints: number;
  dropped: number;
  cpuShare: { sims: number; broker: number; middleware: number };
  rssMiB: { sims: number; broker: number; middleware: number };
  pass: boolean;
  why: string;
}

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

/**
 * Points stored for arms whose id starts with `prefix`: servo positions/angles and health, and
 * the profile each arm announces and the control events it sends (all a simulator makes).
 */
async function storedPoints(url: string, db: string, prefix: string): Promise<number> {
  const where = `WHERE "arm" =~ /^${prefix}/`;
  const [servo, profile, audit] = await Promise.all([
    firstRow(url, db, `SELECT count("angle"), count("temp") FROM "servo" ${where}`),
    firstRow(url, db, `SELECT count("name") FROM "profile" ${where}`),
    firstRow(url, db, `SELECT count("by") FROM "audit" ${where}`),
  ]);
  return [servo[1], servo[2], profile[1], audit[1]].reduce<number>((n, v) => n + Number(v ?? 0), 0);
}

export const fleetSection: Section = {
  id: 'fleet',
  title: 'Fleet: N simulated arms at 50 Hz through Mosquitto into the middleware and InfluxDB',
  async run(ctx): Promise<SectionOutput> {
    const counts = ctx.quick ? [1, 10, 50, 100] : [1, 10, 50, 100, 200, 400, 800];
    const windowS = ctx.quick ? 5 : 15;
    const brokerPid = findPid(ctx.broker.confFile);
    const mw = await startMiddleware(
      {
        MQTT_URL: ctx.broker.url,
        MQTT_CLIENT_ID: `bench-fleet-${process.pid}`,
        INFLUX_URL: ctx.influx.url,
        INFLUX_BUCKET: ctx.influx.bucket,
        SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, 'spool-fleet-')),
        FLUSH_INTERVAL_MS: String(FLUSH_MS),
        THERMAL_WATCH: 'false',
      },
      path.join(ctx.logDir, 'fleet-middleware.log'),
    );
    const counter = await connectMqtt(ctx.broker.url, `bench-fleet-count-${process.pid}`);
    let seen = 0;
    let prefix = '';
    counter.on('message', (topic) => {
      if (topic.startsWith(`arm/${prefix}`)) seen++;
    });
    await counter.subscribeAsync('arm/+/status', { qos: 0 });
    const steps: FleetStep[] = [];
    try {
      for (const arms of counts) {
        prefix = `fleet${arms}-`;
        ctx.log(`fleet: ${arms} arms at ${RATE_HZ} Hz`);
        const before = await mw.metrics();
        const agent = startAgent(
          'fleet',
          [ctx.broker.url, String(arms), String(RATE_HZ), prefix],
          path.join(ctx.logDir, `fleet-sims-${arms}.log`),
        );
        try {
          await agentResult<{ ready: number }>(agent, 60_000 + arms * 500);
          await sleep(1000); // past the first announcements
          const meters = [agent.pid, brokerPid ?? -1, mw.child.pid].map((p) => cpuMeter(p));
          for (const m of meters) m.start();
          const seen0 = seen;
          await sleep(windowS * 1000);
          const [sims, broker, middleware] = meters.map((m) => m.stop().share);
          const rss = {
            sims: round(rssMiB(agent.pid), 1),
            broker: round(rssMiB(brokerPid), 1),
            middleware: round(rssMiB(mw.child.pid), 1),
          };
          const seenInWindow = seen - seen0;
          await agent.stop(10_000);
          await sleep(FLUSH_MS + 500);
          const after = await mw.metrics();
          const produced = (after.points_produced_total ?? 0) - (before.points_produced_total ?? 0);
          const msgs =
            (after['messages_total{topic="status"}'] ?? 0) -
            (before['messages_total{topic="status"}'] ?? 0);
          const dropped = (after.points_dropped_total ?? 0) - (before.points_dropped_total ?? 0);
          const { got } = await waitForCount(
            () => storedPoints(ctx.influx.url, ctx.influx.db, prefix),
            produced,
            30_000,
            5000,
          );
          const perArmHz = seenInWindow / arms / windowS;
          const why =
            got !== produced
              ? `${produced - got} points missing`
              : dropped > 0
                ? `${dropped} points dropped`
                : perArmHz < SIM_HELD * RATE_HZ
                  ? `the simulators reached ${perArmHz.toFixed(1)} Hz an arm only`
                  : '';
          steps.push({
            arms,
            windowS,
            perArmHz: round(perArmHz, 1),
            seenMessages: seenInWindow,
            middlewareMessages: msgs,
            producedPoints: produced,
            storedPoints: got,
            dropped,
            cpuShare: {
              sims: round(sims ?? NaN, 3),
              broker: round(broker ?? NaN, 3),
              middleware: round(middleware ?? NaN, 3),
            },
            rssMiB: rss,
            pass: why === '',
            why,
          });
          ctx.log(`fleet: ${arms} arms → ${why || 'ok'}`);
          if (why) break;
        } finally {
          await agent.stop(10_000);
        }
      }
    } finally {
      await counter.endAsync().catch(() => {});
      await mw.child.stop();
    }
    const passing = steps.filter((s) => s.pass);
    const best = passing[passing.length - 1];
    const one = steps[0];
    const perArm = (s: FleetStep | undefined, k: keyof FleetStep['cpuShare']) =>
      s ? `${fmt((s.cpuShare[k] / s.arms) * 100, 2)} % of a core, ${fmt(s.rssMiB[k], 0)} MiB` : '—';
    const rows: Row[] = [
      {
        figure: `arms at ${RATE_HZ} Hz through Mosquitto into the middleware, highest step held`,
        value: best ? `${best.arms} (steps ${counts.join(', ')})` : 'none',
        baseline: one ? `1 arm: ${one.perArmHz} Hz seen` : '—',
        target: 'reported (skeleton; every point stored is checked per step)',
        met: null,
      },
      ...(['sims', 'broker', 'middleware'] as const).map((k) => ({
        figure: `${k} per arm at ${best?.arms ?? '—'} arms (CPU), resident memory in all`,
        value: perArm(best, k),
        baseline: `1 arm: ${perArm(one, k)}`,
        target: 'reported',
        met: null,
      })),
    ];
    return {
      rows,
      settings: {
        counts,
        windowS,
        rateHz: RATE_HZ,
        flushIntervalMs: FLUSH_MS,
        broker: 'mosquitto',
      },
      data: { steps },
    };
  },
};
