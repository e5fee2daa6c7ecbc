/**
 * Section 2: ingest. First the ceiling, influxd's own with its best client ("influxd best
 * client"): the points of N 6-servo state groups, pre-formatted as the middleware's line
 * protocol and gzipped before the clock starts, POSTed to /api/v2/write in batches of 5,000 by
 * 4 concurrent writers, before and after the ramps (the mean is the ceiling; the machine's load
 * moves). Beside it, for reference, the old baseline: 1,000-line batches, one request at a time.
 * Then the middleware under a ramp of status rates, as fractions of the first ceiling
 * measurement, until a step fails (past the list, ×1.25 a step up to 4× the ceiling): with its
 * defaults (WRITE_CONCURRENCY 4, WRITE_GZIP=auto: plain to this loopback influxd) and, in a
 * full run, with one write at a time and no gzip (how it wrote before issue 19). A separate publisher process (bench/agents/publisher.ts) sends pre-built
 * groups at R messages/s for D s, QoS 0 as an arm does; the step passes when every point is
 * in InfluxDB (counted per arm tag), /metrics says dropped = 0, the publisher kept the rate,
 * and the backlog was written
 * within FLUSH_INTERVAL_MS + max(2 s, D/4) of the last message (a middleware falling behind
 * would need longer).
 * CPU = utime + stime of the middleware (and of influxd) from /proc over the step.
 */
import fs from 'node:fs';
import path from 'node:path';
import {
  agentResult,
  countPoints,
  startAgent,
  startMiddleware,
  waitForCount,
} from './lib/stack.ts';
import { BEST_CLIENT, ceiling, SEQUENTIAL_CLIENT } from './lib/influx-ceiling.ts';
import { cpuMeter, cpuSeconds, findPid } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { boundedRatio, stepVerdict } from './lib/zero-loss.ts';
import { barChartSvg } from './lib/svg.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const BATCH = 1000;
const FLUSH_MS = 5000;

/**
 * The middleware's write settings in a ramp: the defaults, and one write at a time without gzip
 * (how it wrote before issue 19; the seal's fsync and the unlink are off the main thread in both).
 */
const MIDDLEWARE_SHAPES: { name: string; env: Record<string, string> }[] = [
  { name: 'defaults (4 writes in flight; WRITE_GZIP=auto: plain on loopback)', env: {} },
  {
    name: 'one write at a time, no gzip (WRITE_CONCURRENCY=1, WRITE_GZIP=false)',
    env: { WRITE_CONCURRENCY: '1', WRITE_GZIP: 'false' },
  },
];

interface Step {
  offeredPerS: number;
  seconds: number;
  sent: number;
  publishedPerS: number;
  expectedPoints: number;
  storedPoints: number;
  lost: number;
  droppedDelta: number;
  drainS: number;
  /** Groups stored ÷ seconds of publishing: equals the published rate when nothing is lost. */
  storedGroupsPerS: number;
  /** Groups stored ÷ seconds from first message to last point written (flush wait included). */
  storedGroupsPerSInclDrain: number;
  middlewareCpuMsPer1000: number;
  middlewareCpuShare: number;
  influxdCpuMsPer1000: number;
  pass: boolean;
  why: string;
}

/** Ramp rates: the fractions of the ceiling, then ×1.25 a step up to 4× it, until a step fails. */
function* rampRates(ceilGroupsPerS: number, fractions: readonly number[]): Generator<number> {
  let rate = 0;
  for (const f of fractions) yield (rate = Math.max(10, Math.round(ceilGroupsPerS * f)));
  while ((rate = Math.round(rate * 1.25)) <= 4 * ceilGroupsPerS) yield rate;
}

/** One middleware (started with `env` over the bench's settings) under a ramp until a step fails. */
async function rampMiddleware(
  ctx: BenchContext,
  tag: string,
  env: Record<string, string>,
  rates: Iterable<number>,
  seconds: number,
  t0: { ms: number },
  influxPid: number | undefined,
): Promise<Step[]> {
  const spool = fs.mkdtempSync(path.join(ctx.logDir, `spool-${tag}-`));
  const mw = await startMiddleware(
    {
      MQTT_URL: ctx.broker.url,
      MQTT_CLIENT_ID: `bench-ingest-${tag}-${process.pid}`,
      INFLUX_URL: ctx.influx.url,
      INFLUX_BUCKET: ctx.influx.bucket,
      SPOOL_DIR: spool,
      WRITE_MODE: 'batch',
      ...env,
    },
    path.join(ctx.logDir, `ingest-middleware-${tag}.log`),
  );
  const steps: Step[] = [];
  try {
    for (const rate of rates) {
      const arm = `ing-${tag}-${rate}`;
      ctx.log(`ingest (${tag}): ${rate} groups/s for ${seconds} s`);
      const before = await mw.metrics();
      const mwCpu = cpuMeter(mw.child.pid);
      const infCpu = influxPid ? cpuMeter(influxPid) : undefined;
      const pub = startAgent(
        'publisher',
        [ctx.broker.url, `arm/${arm}/status`, String(rate), String(seconds), String(t0.ms), '0'],
        path.join(ctx.logDir, `ingest-pub-${tag}-${rate}.log`),
      );
      mwCpu.start();
      infCpu?.start();
      const w0 = performance.now();
      const r = await agentResult<{ sent: number; wallS: number; rate: number; sendS: number }>(
        pub,
        seconds * 4000 + 30_000,
      );
      await pub.exited;
      const pubEnd = performance.now();
      t0.ms += r.sent + 1000;
      const want = r.sent * 6;
      const { got } = await waitForCount(
        () => countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm),
        want,
        FLUSH_MS + 30_000,
        FLUSH_MS + 3000,
      );
      const drainS = (performance.now() - pubEnd) / 1000;
      const totalS = (performance.now() - w0) / 1000;
      const c = mwCpu.stop();
      const ic = infCpu?.stop();
      const after = await mw.metrics();
      const dropped = (after.points_dropped_total ?? 0) - (before.points_dropped_total ?? 0);
      const lost = want - got;
      const drainLimitS = FLUSH_MS / 1000 + Math.max(2, 0.25 * seconds);
      const why = stepVerdict({
        rate,
        sent: r.sent,
        sendS: r.sendS,
        missing: lost,
        dropped,
        unit: 'points',
        drainS,
        drainLimitS,
      });
      steps.push({
        offeredPerS: rate,
        seconds,
        sent: r.sent,
        publishedPerS: Math.round(r.sent / r.sendS),
        expectedPoints: want,
        storedPoints: got,
        lost,
        droppedDelta: dropped,
        drainS: round(drainS, 2),
        storedGroupsPerS: Math.round(got / 6 / r.sendS),
        storedGroupsPerSInclDrain: Math.round(got / 6 / totalS),
        middlewareCpuMsPer1000: round((c.cpuS * 1e6) / Math.max(1, got), 3),
        middlewareCpuShare: round(c.cpuS / c.wallS, 3),
        influxdCpuMsPer1000: ic ? round((ic.cpuS * 1e6) / Math.max(1, got), 3) : NaN,
        pass: why === '',
        why,
      });
      ctx.log(`ingest (${tag}): ${rate}/s → ${why || 'ok'}`);
      if (why) break;
    }
  } finally {
    await mw.child.stop();
  }
  return steps;
}

/** The highest passing step, and why the next one failed. */
function verdict(steps: Step[]) {
  const passing = steps.filter((s) => s.pass);
  const best = passing[passing.length - 1];
  const firstFail = steps.find((s) => !s.pass);
  return { best, bestRate: best?.offeredPerS ?? 0, firstFail };
}

export const ingestSection: Section = {
  id: 'ingest',
  title: 'Ingest: middleware → InfluxDB, zero loss',
  async run(ctx): Promise<SectionOutput> {
    const seconds = ctx.quick ? 4 : 10;
    const fractions = ctx.quick
      ? [0.05, 0.25, 0.5, 0.8, 1, 1.25]
      : [0.05, 0.1, 0.25, 0.5, 0.65, 0.8, 0.9, 1, 1.2, 1.5];
    const ceilingGroups = ctx.quick ? 40_000 : 100_000;
    const influxPid = findPid(ctx.influx.confFile);
    // The ceiling is measured before and after the ramps (the machine's load moves); the mean counts.
    ctx.log(`ingest: influxd best client, ${ceilingGroups * 6} points`);
    const ceilBefore = await ceiling(ctx, ceilingGroups, influxPid, 'ceiling-before');
    ctx.log(
      `ingest: ceiling ${ceilBefore.pointsPerS} points/s = ${ceilBefore.groupsPerS} groups/s`,
    );
    const sequential = await ceiling(
      ctx,
      ceilingGroups,
      influxPid,
      'sequential',
      SEQUENTIAL_CLIENT,
    );
    ctx.log(`ingest: one sequential writer, 1,000-line batches: ${sequential.pointsPerS} points/s`);

    const t0 = { ms: Date.now() };
    const shapes = ctx.quick ? MIDDLEWARE_SHAPES.slice(0, 1) : MIDDLEWARE_SHAPES;
    const ramps: { name: string; steps: Step[] }[] = [];
    for (const [k, shape] of shapes.entries()) {
      const steps = await rampMiddleware(
        ctx,
        k === 0 ? 'now' : 'before',
        shape.env,
        rampRates(ceilBefore.groupsPerS, fractions),
        seconds,
        t0,
        influxPid,
      );
      ramps.push({ name: shape.name, steps });
    }
    const ceilAfter = await ceiling(ctx, ceilingGroups, influxPid, 'ceiling-after');
    ctx.log(`ingest: ceiling after the ramps ${ceilAfter.pointsPerS} points/s`);
    const ceil = {
      ...ceilBefore,
      pointsPerS: Math.round((ceilBefore.pointsPerS + ceilAfter.pointsPerS) / 2),
      groupsPerS: Math.round((ceilBefore.groupsPerS + ceilAfter.groupsPerS) / 2),
    };
    const now = verdict(ramps[0]!.steps);
    const old = ramps[1] ? verdict(ramps[1].steps) : null;
    const share = now.bestRate / ceil.groupsPerS;
    // A ramp that ended at the publisher (or passed every step) found no limit of the middleware:
    // its share is a lower bound, which can meet the target but not miss it.
    const atLimit = !!now.firstFail && !now.firstFail.why.startsWith('publisher');
    const shareMet = boundedRatio(
      { rate: now.bestRate, limit: atLimit },
      { rate: ceil.groupsPerS, limit: true },
      0.8,
    ).met;
    const failText = (v: ReturnType<typeof verdict>) =>
      v.firstFail
        ? `; next step ${v.firstFail.offeredPerS.toLocaleString('en')}: ${v.firstFail.why}`
        : '; every step passed';
    const rows: Row[] = [
      {
        figure: 'influxd best client: ceiling, points/s (4 writers, 5,000-line gzip batches)',
        value: `${ceil.pointsPerS.toLocaleString('en')} = ${ceil.groupsPerS.toLocaleString('en')} groups/s (${ceilBefore.pointsPerS.toLocaleString('en')} before, ${ceilAfter.pointsPerS.toLocaleString('en')} after the ramps)`,
        baseline: `one sequential writer, 1,000-line batches: ${sequential.pointsPerS.toLocaleString('en')} points/s`,
        target: 'reported',
        met: null,
      },
      {
        figure: "middleware zero-loss rate ÷ influxd best client's ceiling, same run",
        value: `${atLimit ? '' : '≥ '}${fmt(share, 2)} (${now.bestRate.toLocaleString('en')} groups/s${failText(now)})`,
        baseline: old
          ? `one write at a time, no gzip: ${fmt(old.bestRate / ceil.groupsPerS, 2)} (${old.bestRate.toLocaleString('en')} groups/s${failText(old)})`
          : 'one write at a time, no gzip: not run (--quick)',
        target: '≥ 0.8',
        met: shareMet,
      },
      {
        figure: `Middleware CPU per 1,000 frames (at ${now.bestRate.toLocaleString('en')}/s)`,
        value: now.best
          ? `${fmt(now.best.middlewareCpuMsPer1000, 2)} ms (${fmt(now.best.middlewareCpuShare * 100, 0)} % of a core)`
          : '—',
        baseline: `best client writing direct: ${fmt(ceil.clientCpuMsPer1000, 2)} ms`,
        target: 'reported',
        met: null,
      },
      {
        figure: 'influxd CPU per 1,000 points',
        value: now.best ? `${fmt(now.best.influxdCpuMsPer1000, 2)} ms via middleware` : '—',
        baseline: `${fmt(ceil.influxdCpuMsPer1000, 2)} ms from the best client`,
        target: 'reported',
        met: null,
      },
    ];
    const file = `${ctx.stamp}-ingest.svg`;
    const steps = ramps[0]!.steps;
    fs.writeFileSync(
      path.join(ctx.resultsDir, file),
      barChartSvg({
        title: `Ingest ramp: offered vs stored (influxd best client ${ceil.groupsPerS.toLocaleString('en')} groups/s)`,
        xLabel: 'offered, 6-servo groups/s (✗ = step failed)',
        yLabel: 'groups/s',
        categories: [...steps.map((s) => `${s.offeredPerS}${s.pass ? '' : ' ✗'}`), 'ceiling'],
        series: [
          {
            name: 'published',
            values: [...steps.map((s) => s.publishedPerS), 0],
            colour: '#7570b3',
          },
          {
            name: 'stored, per s of publishing',
            values: [...steps.map((s) => s.storedGroupsPerS), 0],
            colour: '#d95f02',
          },
          {
            name: 'influxd best client',
            values: [...steps.map(() => 0), ceil.groupsPerS],
            colour: '#1b9e77',
          },
        ],
      }),
    );
    return {
      rows,
      plots: [{ file, title: 'Ingest ramp' }],
      settings: {
        secondsPerStep: seconds,
        drainLimitS: FLUSH_MS / 1000 + Math.max(2, 0.25 * seconds),
        fractionsOfCeiling: fractions,
        beyondTheList: '×1.25 a step up to 4× the ceiling, until a step fails',
        ceilingGroups,
        bestClient: BEST_CLIENT,
        sequentialClient: SEQUENTIAL_CLIENT,
        middlewareShapes: shapes,
        batchSize: BATCH,
        flushIntervalMs: FLUSH_MS,
        writeMode: 'batch',
        publishQos: 0,
        subscribeQos: 1,
      },
      data: {
        ceiling: { mean: ceil, before: ceilBefore, after: ceilAfter, sequential },
        ramps,
        influxdPid: influxPid ?? null,
        influxdCpuNow: influxPid ? cpuSeconds(influxPid) : null,
      },
    };
  },
};
