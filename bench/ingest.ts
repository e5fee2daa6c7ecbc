/**
 * Section 2: ingest. First the ceiling: the points of N 6-servo state groups, pre-formatted as
 * the middleware's line protocol, POSTed to InfluxDB's /api/v2/write in batches of 1,000
 * (the middleware's BATCH_SIZE), one request at a time (the middleware's single write loop),
 * before and after the ramp (the mean is the ceiling; the machine's load moves).
 * Then the middleware (batch mode, defaults) under a ramp of status rates, as fractions of the
 * first ceiling measurement: a separate publisher process (bench/agents/publisher.ts) sends pre-built
 * groups at R messages/s for D s, QoS 0 as an arm does; the step passes when every point is
 * in InfluxDB (counted per arm tag), /metrics says dropped = 0, the publisher kept the rate,
 * and the backlog was written
 * within FLUSH_INTERVAL_MS + max(2 s, D/4) of the last message (a middleware falling behind
 * would need longer).
 * CPU = utime + stime of the middleware (and of influxd) from /proc over the step.
 */
import fs from 'node:fs';
import path from 'node:path';
import { angleFromPwm } from '@armtwin/protocol';
import {
  agentResult,
  countPoints,
  startAgent,
  startMiddleware,
  waitForCount,
} from './lib/stack.ts';
import { cpuMeter, cpuSeconds, findPid } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { stepVerdict } from './lib/zero-loss.ts';
import { barChartSvg } from './lib/svg.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const BATCH = 1000;
const FLUSH_MS = 5000;

/** The ceiling: pre-formatted batches straight to /api/v2/write; returns points/s and CPU. */
async function ceiling(
  ctx: BenchContext,
  groups: number,
  influxPid: number | undefined,
  arm: string,
) {
  const t0us = Date.now() * 1000;
  const lines: string[] = [];
  for (let k = 0; k < groups; k++) {
    for (let id = 0; id < 6; id++) {
      const pwm = 1000 + ((k * 7 + id * 150) % 1000);
      lines.push(
        `servo,arm=${arm},id=00${id} pwm=${pwm}i,angle=${angleFromPwm(pwm)} ${t0us + k * 1000}`,
      );
    }
  }
  const bodies: string[] = [];
  for (let i = 0; i < lines.length; i += BATCH) bodies.push(lines.slice(i, i + BATCH).join('\n'));
  const url = `${ctx.influx.url}/api/v2/write?bucket=${encodeURIComponent(ctx.influx.bucket)}&org=&precision=us`;
  // Warm-up: creates the shard and the series of the ceiling's arm before the clock starts.
  await fetch(url, { method: 'POST', body: lines.slice(0, 6 * 100).join('\n') }).then((r) =>
    r.arrayBuffer(),
  );
  const inf = influxPid ? cpuMeter(influxPid) : undefined;
  const self0 = process.cpuUsage();
  inf?.start();
  const w0 = performance.now();
  let failed = 0;
  for (const body of bodies) {
    const res = await fetch(url, {
      method: 'POST',
      body,
      headers: { 'content-type': 'text/plain' },
    });
    if (res.status !== 204) failed++;
    await res.arrayBuffer();
  }
  const wallS = (performance.now() - w0) / 1000;
  const influxCpu = inf?.stop();
  const self = process.cpuUsage(self0);
  const stored = await countPoints(ctx.influx.url, ctx.influx.db, 'servo', 'pwm', arm);
  return {
    points: lines.length,
    stored,
    failedRequests: failed,
    wallS: round(wallS, 3),
    pointsPerS: Math.round(lines.length / wallS),
    groupsPerS: Math.round(lines.length / 6 / wallS),
    clientCpuMsPer1000: round(((self.user + self.system) / 1000 / lines.length) * 1000, 3),
    influxdCpuMsPer1000: influxCpu ? round((influxCpu.cpuS * 1e6) / lines.length, 3) : NaN,
  };
}

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
    // The ceiling is measured before and after the ramp (the machine's load moves); the mean counts.
    ctx.log(`ingest: ceiling, ${ceilingGroups * 6} points in batches of ${BATCH}`);
    const ceilBefore = await ceiling(ctx, ceilingGroups, influxPid, 'ceiling-before');
    ctx.log(
      `ingest: ceiling ${ceilBefore.pointsPerS} points/s = ${ceilBefore.groupsPerS} groups/s`,
    );
    const ceil = { ...ceilBefore };

    const spool = fs.mkdtempSync(path.join(ctx.logDir, 'spool-'));
    const mw = await startMiddleware(
      {
        MQTT_URL: ctx.broker.url,
        MQTT_CLIENT_ID: `bench-ingest-${process.pid}`,
        INFLUX_URL: ctx.influx.url,
        INFLUX_BUCKET: ctx.influx.bucket,
        SPOOL_DIR: spool,
        WRITE_MODE: 'batch',
      },
      path.join(ctx.logDir, 'ingest-middleware.log'),
    );
    const steps: Step[] = [];
    try {
      let t0 = Date.now();
      for (const f of fractions) {
        const rate = Math.max(10, Math.round(ceil.groupsPerS * f));
        const arm = `ing-${rate}`;
        ctx.log(`ingest: ${rate} groups/s for ${seconds} s`);
        const before = await mw.metrics();
        const mwCpu = cpuMeter(mw.child.pid);
        const infCpu = influxPid ? cpuMeter(influxPid) : undefined;
        const pub = startAgent(
          'publisher',
          [ctx.broker.url, `arm/${arm}/status`, String(rate), String(seconds), String(t0), '0'],
          path.join(ctx.logDir, `ingest-pub-${rate}.log`),
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
        t0 += r.sent + 1000;
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
        ctx.log(`ingest: ${rate}/s → ${why || 'ok'}`);
        if (why) break;
      }
    } finally {
      await mw.child.stop();
    }
    const ceilAfter = await ceiling(ctx, ceilingGroups, influxPid, 'ceiling-after');
    ctx.log(`ingest: ceiling after the ramp ${ceilAfter.pointsPerS} points/s`);
    ceil.pointsPerS = Math.round((ceilBefore.pointsPerS + ceilAfter.pointsPerS) / 2);
    ceil.groupsPerS = Math.round((ceilBefore.groupsPerS + ceilAfter.groupsPerS) / 2);
    const passing = steps.filter((s) => s.pass);
    const best = passing[passing.length - 1];
    const bestRate = best?.offeredPerS ?? 0;
    const share = bestRate / ceil.groupsPerS;
    const firstFail = steps.find((s) => !s.pass);
    const rows: Row[] = [
      {
        figure: 'Highest zero-loss status rate, 6-servo groups/s (ramp ceiling)',
        value: `${bestRate.toLocaleString('en')} (${fmt(share * 100, 1)} % of ceiling)${firstFail ? `; next step ${firstFail.offeredPerS.toLocaleString('en')}: ${firstFail.why}` : '; every step passed'}`,
        baseline: `${ceil.groupsPerS.toLocaleString('en')} groups/s = ${ceil.pointsPerS.toLocaleString('en')} points/s direct (mean of ${ceilBefore.pointsPerS.toLocaleString('en')} before and ${ceilAfter.pointsPerS.toLocaleString('en')} after the ramp)`,
        target: '≥ 80 % of ceiling',
        met: share >= 0.8,
      },
      {
        figure: `Middleware CPU per 1,000 frames (at ${bestRate.toLocaleString('en')}/s)`,
        value: best
          ? `${fmt(best.middlewareCpuMsPer1000, 2)} ms (${fmt(best.middlewareCpuShare * 100, 0)} % of a core)`
          : '—',
        baseline: `bench client writing direct: ${fmt(ceil.clientCpuMsPer1000, 2)} ms`,
        target: 'reported',
        met: null,
      },
      {
        figure: 'influxd CPU per 1,000 points',
        value: best ? `${fmt(best.influxdCpuMsPer1000, 2)} ms via middleware` : '—',
        baseline: `${fmt(ceil.influxdCpuMsPer1000, 2)} ms direct`,
        target: 'reported',
        met: null,
      },
    ];
    const file = `${ctx.stamp}-ingest.svg`;
    fs.writeFileSync(
      path.join(ctx.resultsDir, file),
      barChartSvg({
        title: `Ingest ramp: offered vs stored (ceiling ${ceil.groupsPerS.toLocaleString('en')} groups/s direct)`,
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
            name: 'direct line protocol',
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
        ceilingGroups,
        batchSize: BATCH,
        flushIntervalMs: FLUSH_MS,
        writeMode: 'batch',
        publishQos: 0,
        subscribeQos: 1,
      },
      data: {
        ceiling: { mean: ceil, before: ceilBefore, after: ceilAfter },
        steps,
        influxdPid: influxPid ?? null,
        influxdCpuNow: influxPid ? cpuSeconds(influxPid) : null,
      },
    };
  },
};
