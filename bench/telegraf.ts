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
 * Then the same for armtwin's usual message, a 6-servo group (`$TIM:t!{#000P…!…#005P…!}`), for
 * which Telegraf needs a configuration of its own: the `value` parser takes the payload as one
 * string and a Starlark processor splits it into one metric per servo (grok makes one metric per
 * line, and a group is one line).
 * Not the same work: the middleware also stores each frame's angle and checks every frame
 * against the contract; Telegraf stores the pulse width only.
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
import { boundedRatio, stepVerdict } from './lib/zero-loss.ts';
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

/** What each message holds: one stamped frame, or a 6-servo group (the publisher's shapes). */
type Shape = 'frame' | 'group';
const FRAMES_PER_MESSAGE: Record<Shape, number> = { frame: 1, group: 6 };

/** Telegraf's parsing of each shape (inside `[[inputs.mqtt_consumer]]`), and any processor. */
const PARSING: Record<Shape, string> = {
  frame: `  data_format = "grok"
  grok_patterns = ['\\$TIM:%{NUMBER:time:ts-epochmilli}!#%{NUMBER:id:tag}P%{NUMBER:pwm:int}!']`,
  group: `  data_format = "value"
  data_type = "string"`,
};
const PROCESSORS: Record<Shape, string> = {
  frame: '',
  group: `
[[processors.starlark]]
  source = '''
def apply(metric):
    text = metric.fields["value"]
    head, _, body = text.partition("!")
    ns = int(head[5:]) * 1000000
    out = []
    for frame in body.strip("{}").split("!"):
        if len(frame) < 6:
            continue
        m = Metric("servo")
        m.tags["arm"] = metric.tags["arm"]
        m.tags["id"] = frame[1:4]
        m.fields["pwm"] = int(frame[5:])
        m.time = ns
        out.append(m)
    return out
'''
`,
};

/** Telegraf's configuration: every `arm/<id>/status` message, the arm from the topic. */
function telegrafConf(ctx: BenchContext, shape: Shape): string {
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
${PARSING[shape]}
  name_override = "servo"
  [[inputs.mqtt_consumer.topic_parsing]]
    topic = "arm/+/status"
    tags = "_/arm/_"
${PROCESSORS[shape]}
[[outputs.influxdb]]
  urls = ["${ctx.influx.url}"]
  database = "${ctx.influx.db}"
  skip_database_creation = true
  timeout = "10s"
`;
}

async function startTelegraf(ctx: BenchContext, shape: Shape): Promise<Consumer> {
  const conf = path.join(ctx.logDir, `telegraf-${shape}.conf`);
  fs.writeFileSync(conf, telegrafConf(ctx, shape));
  const log = path.join(ctx.logDir, `telegraf-${shape}.log`);
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
  return { name: 'Telegraf', prefix: `tg${shape[0]}`, pid: child.pid, stop: () => child.stop() };
}

async function startArmtwin(ctx: BenchContext, shape: Shape): Promise<Consumer> {
  const mw = await startMiddleware(
    {
      MQTT_URL: ctx.broker.url,
      MQTT_CLIENT_ID: `bench-vs-telegraf-${shape}-${process.pid}`,
      INFLUX_URL: ctx.influx.url,
      INFLUX_BUCKET: ctx.influx.bucket,
      SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, 'spool-tg-')),
      WRITE_MODE: 'batch',
      BATCH_SIZE: String(BATCH),
      FLUSH_INTERVAL_MS: String(FLUSH_MS),
    },
    path.join(ctx.logDir, `telegraf-middleware-${shape}.log`),
  );
  return {
    name: 'middleware',
    prefix: `mw${shape[0]}`,
    pid: mw.child.pid,
    stop: () => mw.child.stop(),
  };
}

/** One ramp: rising rates until a step fails (or the list ends). */
async function ramp(
  ctx: BenchContext,
  c: Consumer,
  rates: readonly number[],
  seconds: number,
  t0: { ms: number },
  shape: Shape,
): Promise<Step[]> {
  const steps: Step[] = [];
  const per = FRAMES_PER_MESSAGE[shape];
  for (const frames of rates) {
    // `rates` are frames/s; the publisher sends messages of `per` frames.
    const rate = Math.round(frames / per);
    const arm = `${c.prefix}-${frames}`;
    ctx.log(`telegraf: ${c.name}, ${frames} frames/s (${shape}) for ${seconds} s`);
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
        shape,
      ],
      path.join(ctx.logDir, `telegraf-pub-${c.prefix}-${frames}.log`),
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
        offeredPerS: frames,
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
    t0.ms += (shape === 'frame' ? Math.ceil(r.sent / 6) : r.sent) + 1000;
    const sentFrames = r.sent * per;
    const { got } = await waitForCount(
      () => countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm),
      sentFrames,
      FLUSH_MS + 30_000,
      FLUSH_MS + 5000,
    );
    const drainS = (performance.now() - pubEnd) / 1000;
    const used = cpu.stop();
    const why = stepVerdict({
      rate,
      sent: r.sent,
      sendS: r.sendS,
      missing: sentFrames - got,
      unit: 'frames',
      drainS,
      drainLimitS: FLUSH_MS / 1000 + Math.max(2, seconds / 4),
    });
    steps.push({
      offeredPerS: frames,
      sent: sentFrames,
      publishedPerS: Math.round(sentFrames / r.sendS),
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

/** The three comparison rows of one message shape. */
function compareRows(result: Record<string, Step[]>, shape: Shape): Row[] {
  const tg = best(result.Telegraf ?? []);
  const mw = best(result.middleware ?? []);
  // A ramp stopped by the publisher (it could not keep the rate on this machine) or by the end
  // of the list found no limit of that consumer: its figure is a lower bound.
  const atLimit = (all: Step[] | undefined) => {
    const last = all?.at(-1);
    return !(
      !last ||
      last.passed ||
      last.why.startsWith('publisher') ||
      last.why.startsWith('the publisher')
    );
  };
  const r = boundedRatio(
    { rate: mw?.offeredPerS ?? 0, limit: atLimit(result.middleware) },
    { rate: tg?.offeredPerS ?? 0, limit: atLimit(result.Telegraf) },
    3,
  );
  // CPU compared at the highest rate both passed, so both did the same work.
  const common = (result.middleware ?? [])
    .filter(
      (m) => m.passed && result.Telegraf?.some((t) => t.passed && t.offeredPerS === m.offeredPerS),
    )
    .at(-1);
  const tgAt = result.Telegraf?.find((t) => t.offeredPerS === common?.offeredPerS);
  const cpuRatio = common && tgAt ? common.cpuPer1000Ms / tgAt.cpuPer1000Ms : NaN;
  const top = (s: Step | undefined, all: Step[] | undefined) =>
    s
      ? `${s.offeredPerS} frames/s${all?.at(-1)?.passed ? ' (the ramp ended before a failure)' : `; next step failed: ${all?.at(-1)?.why}`}`
      : `none passed (${all?.at(-1)?.why ?? 'not run'})`;
  const what =
    shape === 'frame'
      ? 'one `$TIM`-stamped frame per message (mqtt_consumer + grok → InfluxDB 1.8)'
      : '6-servo groups, one per message (mqtt_consumer + value parser + Starlark split → InfluxDB 1.8)';
  return [
    {
      figure: `Telegraf: highest zero-loss rate, ${what}`,
      value: top(tg, result.Telegraf),
      baseline: `middleware: ${top(mw, result.middleware)}`,
      target: 'reported',
      met: null,
    },
    {
      figure: `middleware ÷ Telegraf, highest zero-loss frames/s, same frames, same run (${shape === 'frame' ? 'single frames' : '6-servo groups'})`,
      value:
        r.kind === 'exact'
          ? `${fmt(r.ratio, 2)}×`
          : r.kind === 'at least'
            ? `≥ ${fmt(r.ratio, 2)}×: Telegraf's ramp ended at its limit, the middleware's at the publisher's or the list's end`
            : r.kind === 'at most'
              ? `≤ ${fmt(r.ratio, 2)}×: the middleware's ramp ended at its limit, Telegraf's at the publisher's or the list's end`
              : `${fmt(r.ratio, 2)}×, not a ratio of limits: both ramps ended at the publisher's limit or the list's end, so both only passed up to there`,
      baseline: 'issue 19: 1.8× (an outside measurement, single frames)',
      target: '≥ 3×',
      met: r.met,
    },
    {
      figure: `CPU per 1,000 frames at the highest rate both passed, middleware ÷ Telegraf (${shape === 'frame' ? 'single frames' : '6-servo groups'})`,
      value: `${fmt(cpuRatio, 2)} (${fmt(common?.cpuPer1000Ms, 1)} vs ${fmt(tgAt?.cpuPer1000Ms, 1)} ms at ${common?.offeredPerS ?? '—'} frames/s)`,
      baseline: 'issue 19: 0.63 (7.6 vs 12.1 ms, single frames)',
      target: '≤ 0.33',
      met: Number.isFinite(cpuRatio) ? cpuRatio <= 1 / 3 : null,
    },
  ];
}

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
    // Frames/s, for both shapes (a group carries 6).
    const rates = ctx.quick
      ? [4000, 16_000, 32_000, 64_000, 128_000, 192_000, 256_000]
      : [10_000, 20_000, 40_000, 60_000, 80_000, 100_000, 150_000, 200_000, 300_000];
    const t0 = { ms: Date.now() };
    const results: Record<Shape, Record<string, Step[]>> = { frame: {}, group: {} };
    for (const shape of ['frame', 'group'] as const) {
      for (const start of [startTelegraf, startArmtwin]) {
        const c = await start(ctx, shape);
        try {
          results[shape][c.name] = await ramp(ctx, c, rates, seconds, t0, shape);
        } finally {
          await c.stop();
        }
      }
    }
    return {
      rows: [...compareRows(results.frame, 'frame'), ...compareRows(results.group, 'group')],
      settings: {
        seconds,
        rates,
        batch: BATCH,
        flushMs: FLUSH_MS,
        publishQos: 0,
        subscribeQos: 1,
        shapes: ['frame', 'group'],
      },
      data: { steps: results },
    };
  },
};
