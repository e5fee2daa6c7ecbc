/**
 * Section 1: round trip of `$PNG:n!` through Mosquitto and the simulator, against a bare
 * mqtt.js echo client on the same broker (bench/agents/echo.ts). The pinger (this process)
 * publishes on the control topic at QoS 1 and listens on the status topic at QoS 0, as a HUD
 * does; times are `process.hrtime.bigint()` at `publish()` and at the `message` event.
 * Runs: 101 and 1,001 pings one at a time (seed 002), then N pings at 1 kHz open loop (seed
 * 004), split in blocks that alternate target and baseline (ABBA…) so drift hits both.
 * Loss = sequence numbers in the run with no echo after a grace period.
 */
import path from 'node:path';
import { connectMqtt, startAgent, agentResult, startSim } from './lib/stack.ts';
import { startMosquitto } from '../tests/helpers/services.ts';
import { histogram, round, summarize, type Summary } from './lib/stats.ts';
import { barChartSvg } from './lib/svg.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';
import fs from 'node:fs';
import { merge, Pinger, type Path, type PingRun } from './lib/pinger.ts';

const ARM = 'bench-rtt';
const brief = (r: PingRun) => {
  const s = summarize(r.rttMs);
  const rnd = (v: number) => round(v, 4);
  return {
    sent: r.sent,
    received: r.received,
    lost: r.lost,
    duplicates: r.duplicates,
    outOfOrder: r.outOfOrder,
    durationS: round(r.durationS, 2),
    rateHz: round(r.sent / r.durationS, 1),
    rttMs: {
      n: s.n,
      mean: rnd(s.mean),
      min: rnd(s.min),
      p50: rnd(s.p50),
      p95: rnd(s.p95),
      p99: rnd(s.p99),
      max: rnd(s.max),
    },
  };
};

const stats = (s: Summary) =>
  `mean ${fmt(s.mean, 3)} / p50 ${fmt(s.p50, 3)} / p95 ${fmt(s.p95, 3)} / p99 ${fmt(s.p99, 3)} / max ${fmt(s.max, 2)}`;

export const rttSection: Section = {
  id: 'rtt',
  title: 'Round trip ($PNG) through Mosquitto and the simulator',
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const paced = ctx.quick ? 5000 : 60_000;
    const blocks = ctx.quick ? 2 : 6;
    const settings = {
      sequential: [101, 1001],
      pacedCount: paced,
      pacedHz: 1000,
      pacedBlocks: blocks,
      simStateRateHz: 50,
      broker: 'set_tcp_nodelay true (and a second broker on defaults for the Nagle row)',
      pingerNoDelay: true,
      echo: 'bench/agents/echo.ts: mqtt.js defaults, subscribe QoS 1, republish QoS 0',
      controlQos: 1,
      statusQos: 0,
    };
    const out: Record<string, { sim: PingRun; echo: PingRun }> = {};
    const simLog = path.join(ctx.logDir, 'rtt-sim.log');
    await withPaths(ctx, ctx.broker.url, 'rtt', async (pinger, simPath, echoPath) => {
      for (const n of [101, 1001]) {
        ctx.log(`rtt: ${n} pings one at a time, alternating sim and echo`);
        const [s, e] = await pinger.alternating(simPath, echoPath, n);
        out[`seq${n}`] = { sim: s, echo: e };
      }
      ctx.log(`rtt: ${paced} pings at 1 kHz in ${blocks} alternating blocks`);
      const simRuns: PingRun[] = [];
      const echoRuns: PingRun[] = [];
      const per = Math.ceil(paced / blocks);
      for (let b = 0; b < blocks; b++) {
        const order = b % 2 === 0 ? [echoPath, simPath] : [simPath, echoPath];
        for (const p of order) {
          const r = await pinger.paced(p, per, 1000);
          (p.name === 'sim' ? simRuns : echoRuns).push(r);
        }
      }
      out.paced = { sim: merge(simRuns), echo: merge(echoRuns) };
    });
    // The same 101 pings on a Mosquitto with its default config (set_tcp_nodelay false).
    ctx.log('rtt: 101 pings on a Mosquitto with default settings (Nagle on)');
    const plain = await startMosquitto({ tcpNoDelay: false });
    try {
      await withPaths(ctx, plain.url, 'rtt-nagle', async (pinger, simPath, echoPath) => {
        const [s, e] = await pinger.alternating(simPath, echoPath, 101);
        out.nagle101 = { sim: s, echo: e };
      });
    } finally {
      await plain.dispose();
    }
    // The simulator logs the first of each kind of problem; a rate limit explains lost pings.
    const simProblems = [...readText(simLog).matchAll(/"kind":"([^"]+)","msg":"([^"]*)"/g)].map(
      (m) => `${m[1]}: ${m[2]}`,
    );
    const limited = simProblems.find((p) => p.startsWith('control:rate-limit'));
    const rows: Row[] = [];
    for (const [key, label] of [
      ['seq101', '101 pings, one at a time'],
      ['seq1001', '1,001 pings, one at a time'],
      ['paced', `${paced.toLocaleString('en')} pings at 1 kHz`],
      ['nagle101', '101 pings, Mosquitto defaults (Nagle on)'],
    ] as const) {
      const { sim: s, echo: e } = out[key]!;
      const ss = summarize(s.rttMs);
      const es = summarize(e.rttMs);
      const info = key === 'nagle101'; // shows the broker setting's effect; not a target row
      const ratio = ss.p99 / es.p99;
      rows.push(
        {
          figure: `RTT, ${label}: loss`,
          value: `${s.lost} / ${s.sent}${s.lost && limited && !info ? ` (sim log: ${limited.split(' (')[0]})` : ''}`,
          baseline: `${e.lost} / ${e.sent}`,
          target: '0',
          met: s.lost === 0,
        },
        {
          figure: `RTT ms, ${label}`,
          value: stats(ss),
          baseline: stats(es),
          target: info ? 'reported' : 'p50 < 1 ms',
          met: info ? null : ss.p50 < 1,
        },
        {
          figure: `RTT, ${label}: p99 ÷ bare-echo p99`,
          value: fmt(ratio, 2),
          baseline: '1.00',
          target: info ? 'reported' : '≤ 1.5',
          met: info ? null : ratio <= 1.5,
        },
      );
    }
    const pacedRuns = out.paced!;
    const plot = histogramPlot(pacedRuns.sim.rttMs, pacedRuns.echo.rttMs, paced);
    fs.writeFileSync(path.join(ctx.resultsDir, `${ctx.stamp}-rtt-hist.svg`), plot);
    return {
      rows,
      settings,
      plots: [
        {
          file: `${ctx.stamp}-rtt-hist.svg`,
          title: `RTT histogram, ${paced} pings at 1 kHz (cf. seed 000 Fig. 10)`,
        },
      ],
      data: {
        simLogProblems: simProblems,
        ...Object.fromEntries(
          Object.entries(out).map(([k, v]) => [k, { sim: brief(v.sim), echo: brief(v.echo) }]),
        ),
      },
    };
  },
};

const readText = (file: string) => {
  try {
    return fs.readFileSync(file, 'utf8');
  } catch {
    return '';
  }
};

/** Starts a sim and an echo agent on `url`, and a pinger client; runs `fn`; stops them all. */
async function withPaths(
  ctx: BenchContext,
  url: string,
  tag: string,
  fn: (pinger: Pinger, sim: Path, echo: Path) => Promise<void>,
): Promise<void> {
  const sim = await startSim(url, ARM, 50, path.join(ctx.logDir, `${tag}-sim.log`));
  const echo = startAgent(
    'echo',
    [url, 'bench/echo/control', 'bench/echo/status', '900'],
    path.join(ctx.logDir, `${tag}-echo.log`),
  );
  const client = await connectMqtt(url, `bench-pinger-${process.pid}-${tag}`);
  try {
    // The pinger is shared by both paths; Nagle off on its own socket keeps it out of the figure.
    (client.stream as unknown as { setNoDelay?: (on: boolean) => void }).setNoDelay?.(true);
    await agentResult(echo, 30_000);
    await client.subscribeAsync([`arm/${ARM}/status`, 'bench/echo/status'], { qos: 0 });
    const pinger = new Pinger(client);
    const simPath: Path = {
      name: 'sim',
      control: `arm/${ARM}/control`,
      status: `arm/${ARM}/status`,
    };
    const echoPath: Path = {
      name: 'echo',
      control: 'bench/echo/control',
      status: 'bench/echo/status',
    };
    await pinger.sequential(echoPath, 20); // warm-up, not recorded
    await pinger.sequential(simPath, 20);
    await fn(pinger, simPath, echoPath);
  } finally {
    await client.endAsync().catch(() => {});
    await echo.stop();
    await sim.stop();
  }
}

/** Frequency (% of pings) per RTT bin, simulator beside bare echo, like seed 000's Fig. 10. */
function histogramPlot(sim: number[], echo: number[], n: number): string {
  const hi = Math.max(0.5, summarize([...sim, ...echo]).p99 * 1.2);
  const bins = 30;
  const w = hi / bins;
  const pct = (xs: number[]) =>
    histogram(xs, 0, hi, bins).map((c) => round((100 * c) / Math.max(1, xs.length), 2));
  return barChartSvg({
    title: `$PNG round trip, ${n.toLocaleString('en')} pings at 1 kHz on 127.0.0.1 (last bin: ≥ ${hi.toFixed(2)} ms)`,
    xLabel: 'RTT, ms (bin start)',
    yLabel: '% of pings',
    categories: Array.from({ length: bins }, (_, i) => (i * w).toFixed(2)),
    labelEvery: 2,
    series: [
      { name: 'via armtwin sim', values: pct(sim), colour: '#d95f02' },
      { name: 'bare mqtt.js echo', values: pct(echo), colour: '#1b9e77' },
    ],
  });
}
