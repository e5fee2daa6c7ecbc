/**
 * Section: Telegraf side by side (issue 19). What a user would pick instead of armtwin's
 * middleware: Telegraf's `mqtt_consumer` parsing the frames with its own grok parser, one metric
 * per servo reading, into the same InfluxDB. Both take the same frames from the same publisher
 * (bench/agents/publisher.ts, `frame` shape: one `$TIM`-stamped position frame per message, the
 * shape both can parse, QoS 0 as an arm sends), one after the other, each with batches of 1,000 points flushed every
 * second. A ramp of publish rates for each; a step passes when every frame is a point in
 * InfluxDB (counted per arm tag), the publisher kept the rate, and the backlog was written within
 * 1 s + max(2 s, D/4) of the last message. Each consumer's figure is its highest passing rate,
 * and CPU (utime + stime from /proc) per 1,000 frames at that rate.
 * Not the same work: the middleware also stores each frame's angle and checks every frame
 * against the contract; Telegraf stores the pulse width only. Single-frame messages only:
 * armtwin's usual 6-servo groups need a Telegraf configuration of their own (not done).
 */
import fs from 'node:fs';
import path from 'node:path';
import {
  agentResult,
  countPoints,
  REPO,
  startAgent,
  startMiddleware,
  waitForCount,
} from './lib/stack.ts';
import { cpuMeter, spawnChild, until, type Child } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { stepVerdict } from './lib/zero-loss.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const TELEGRAF = path.join(REPO, '.tools', 'bin', 'telegraf');
const FLUSH_MS = 1000;
const BATCH = 1000;

interface Step {
  offeredPerS: number;
  sent: number;
  publishedPerS: number;
  stored: number;
  drainS: number;
  cpuPer1000Ms: number;
  /** The consumer's CPU over the step: cores (utime + stime ÷ wall), and the wall, s. */
  cpuCores: number;
  wallS: number;
  passed: boolean;
  why: string;
}

interface Consumer {
  name: string;
  /** Arm id prefix: the consumer stores under `<prefix>-<rate>`. */
  prefix: string;
  pid: number;
  stop(): Promise<void>;
}

/** Telegraf's configuration: every `arm/<id>/status` message, the arm from the topic. */
function telegrafConf(ctx: BenchContext): string {
  const mqtt = new URL(ctx.broker.url);
  return `[agent]
  interval = "1s"
  flush_interval = "${FLUSH_MS / 1000}s"
  flush_jitter = "0s"
  metric_batch_size = ${BATCH}
  metric_buffer_limit = 10000000
  omit_hostname = true

[[inputs.mqtt_consumer]]
  servers = ["tcp://${mqtt.hostname}:${mqtt.port}"]
  topics = ["arm/+/status"]
  qos = 1
  client_id = "bench-telegraf-${process.pid}"
  topic_tag = ""
  data_format = "grok"
  grok_patterns = ['\\$TIM:%{NUMBER:time:ts-epochmilli}!#%{NUMBER:id:tag}P%{NUMBER:pwm:int}!']
  name_override = "servo"
  [[inputs.mqtt_consumer.topic_parsing]]
    topic = "arm/+/status"
    tags = "_/arm/_"

[[outputs.influxdb]]
  urls = ["${ctx.influx.url}"]
  database = "${ctx.influx.db}"
  skip_database_creation = true
  timeout = "10s"
`;
}

async function startTelegraf(ctx: BenchContext): Promise<Consumer> {
  const conf = path.join(ctx.logDir, 'telegraf.conf');
  fs.writeFileSync(conf, telegrafConf(ctx));
  const log = path.join(ctx.logDir, 'telegraf.log');
  const child: Child = spawnChild(TELEGRAF, ['--config', conf], { logFile: log });
  // Ready once its MQTT client is subscribed (it logs "Connected").
  const ok = await until(
    async () => fs.existsSync(log) && /Connected \[tcp:/.test(fs.readFileSync(log, 'utf8')),
    30_000,
    100,
  );
  if (!ok) {
    await child.stop();
    throw new Error(`telegraf did not connect (log: ${log})`);
  }
  return { name: 'Telegraf', prefix: 'tg', pid: child.pid, stop: () => child.stop() };
}

async function startArmtwin(ctx: BenchContext): Promise<Consumer> {
  const mw = await startMiddleware(
    {
      MQTT_URL: ctx.broker.url,
      MQTT_CLIENT_ID: `bench-vs-telegraf-${process.pid}`,
      INFLUX_URL: ctx.influx.url,
      INFLUX_BUCKET: ctx.influx.bucket,
      SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, 'spool-tg-')),
      WRITE_MODE: 'batch',
      BATCH_SIZE: String(BATCH),
      FLUSH_INTERVAL_MS: String(FLUSH_MS),
    },
    path.join(ctx.logDir, 'telegraf-middleware.log'),
  );
  return { name: 'middleware', prefix: 'mw', pid: mw.child.pid, stop: () => mw.child.stop() };
}

/** One ramp: rising rates until a step fails (or the list ends). */
async function ramp(
  ctx: BenchContext,
  c: Consumer,
  rates: readonly number[],
  seconds: number,
  t0: { ms: number },
): Promise<Step[]> {
  const steps: Step[] = [];
  for (const rate of rates) {
    const arm = `${c.prefix}-${rate}`;
    ctx.log(`telegraf: ${c.name}, ${rate} frames/s for ${seconds} s`);
    const cpu = cpuMeter(c.pid);
    const pub = startAgent(
      'publisher',
      [
        ctx.broker.url,
        `arm/${arm}/status`,
        String(rate),
        String(seconds),
        String(t0.ms),
        '0',
        'frame',
      ],
      path.join(ctx.logDir, `telegraf-pub-${c.prefix}-${rate}.log`),
    );
    cpu.start();
    let r: { sent: number; sendS: number };
    try {
      r = await agentResult<{ sent: number; sendS: number }>(pub, seconds * 4000 + 30_000);
    } catch (err) {
      await pub.stop();
      cpu.stop();
      const why = `the publisher did not finish (${(err as Error).message})`;
      steps.push({
        offeredPerS: rate,
        sent: 0,
        publishedPerS: 0,
        stored: 0,
        drainS: NaN,
        cpuPer1000Ms: NaN,
        cpuCores: NaN,
        wallS: NaN,
        passed: false,
        why,
      });
      break;
    }
    await pub.exited;
    const pubEnd = performance.now();
    t0.ms += Math.ceil(r.sent / 6) + 1000;
    const { got } = await waitForCount(
      () => countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm),
      r.sent,
      FLUSH_MS + 30_000,
      FLUSH_MS + 5000,
    );
    const drainS = (performance.now() - pubEnd) / 1000;
    const used = cpu.stop();
    const why = stepVerdict({
      rate,
      sent: r.sent,
      sendS: r.sendS,
      missing: r.sent - got,
      unit: 'frames',
      drainS,
      drainLimitS: FLUSH_MS / 1000 + Math.max(2, seconds / 4),
    });
    steps.push({
      offeredPerS: rate,
      sent: r.sent,
      publishedPerS: Math.round(r.sent / r.sendS),
      stored: got,
      drainS: round(drainS, 2),
      cpuPer1000Ms: round((used.cpuS * 1000 * 1000) / Math.max(1, got), 3),
      cpuCores: round(used.share, 3),
      wallS: round(used.wallS, 2),
      passed: why === '',
      why,
    });
    if (why) break;
  }
  return steps;
}

const best = (steps: Step[]) => [...steps].reverse().find((s) => s.passed);

export const telegrafSection: Section = {
  id: 'telegraf',
  title: 'Telegraf side by side: the same frames into the same InfluxDB',
  precheck() {
    return fs.existsSync(TELEGRAF)
      ? null
      : `${TELEGRAF} missing: run scripts/build-telegraf.sh (a custom build, about a minute)`;
  },
  async run(ctx): Promise<SectionOutput> {
    const seconds = ctx.quick ? 3 : 5;
    const rates = ctx.quick
      ? [2000, 8000, 16_000, 32_000]
      : [10_000, 20_000, 40_000, 60_000, 80_000, 100_000, 150_000, 200_000, 300_000];
    const t0 = { ms: Date.now() };
    const result: Record<string, Step[]> = {};
    for (const start of [startTelegraf, startArmtwin]) {
      const c = await start(ctx);
      try {
        result[c.name] = await ramp(ctx, c, rates, seconds, t0);
      } finally {
        await c.stop();
      }
    }
    const tg = best(result.Telegraf ?? []);
    const mw = best(result.middleware ?? []);
    // A ramp stopped by the publisher (it could not keep the rate on this machine) or by the end
    // of the list found no limit of that consumer: its figure is a lower bound.
    const bounded = (all: Step[] | undefined) => {
      const last = all?.at(-1);
      return (
        !last ||
        last.passed ||
        last.why.startsWith('publisher') ||
        last.why.startsWith('the publisher')
      );
    };
    const lowerBound = bounded(result.Telegraf) || bounded(result.middleware);
    const ratio = tg && mw ? mw.offeredPerS / tg.offeredPerS : NaN;
    // CPU compared at the highest rate both passed, so both did the same work.
    const common = (result.middleware ?? [])
      .filter(
        (m) =>
          m.passed && result.Telegraf?.some((t) => t.passed && t.offeredPerS === m.offeredPerS),
      )
      .at(-1);
    const tgAt = result.Telegraf?.find((t) => t.offeredPerS === common?.offeredPerS);
    const cpuRatio = common && tgAt ? common.cpuPer1000Ms / tgAt.cpuPer1000Ms : NaN;
    const top = (s: Step | undefined, all: Step[] | undefined) =>
      s
        ? `${s.offeredPerS} frames/s${all?.at(-1)?.passed ? ' (the ramp ended before a failure)' : `; next step failed: ${all?.at(-1)?.why}`}`
        : `none passed (${all?.at(-1)?.why ?? 'not run'})`;
    const rows: Row[] = [
      {
        figure:
          'Telegraf: highest zero-loss rate, one `$TIM`-stamped frame per message (mqtt_consumer + grok → InfluxDB 1.8)',
        value: top(tg, result.Telegraf),
        baseline: `middleware: ${top(mw, result.middleware)}`,
        target: 'reported',
        met: null,
      },
      {
        figure: 'middleware ÷ Telegraf, highest zero-loss frames/s, same frames, same run',
        value: lowerBound
          ? `${fmt(ratio, 2)}×, not a ratio of limits: a ramp ended at the publisher's limit or the list's end, so both only passed up to there`
          : `${fmt(ratio, 2)}×`,
        baseline: 'issue 19: 1.8× (an outside measurement)',
        target: '≥ 3×',
        met: lowerBound || !Number.isFinite(ratio) ? null : ratio >= 3,
      },
      {
        figure: 'CPU per 1,000 frames at the highest rate both passed, middleware ÷ Telegraf',
        value: `${fmt(cpuRatio, 2)} (${fmt(common?.cpuPer1000Ms, 1)} vs ${fmt(tgAt?.cpuPer1000Ms, 1)} ms at ${common?.offeredPerS ?? '—'} frames/s)`,
        baseline: 'issue 19: 0.63 (7.6 vs 12.1 ms)',
        target: '≤ 0.33',
        met: Number.isFinite(cpuRatio) ? cpuRatio <= 1 / 3 : null,
      },
    ];
    return {
      rows,
      settings: {
        seconds,
        rates,
        batch: BATCH,
        flushMs: FLUSH_MS,
        publishQos: 0,
        subscribeQos: 1,
        shape: 'frame',
      },
      data: { steps: result },
    };
  },
};
