/**
 * Section `cluster` (issue 34 items 3 and 5, not in the default set): N simulated arms at 50 Hz
 * on a 3-node NATS cluster (tests/helpers/nats-cluster.ts, docs/cluster.md), a third of them
 * preferring each node, into two middlewares sharing the stream (`NATS_URL`) and InfluxDB; N
 * stepped up, a fresh cluster per step. Per step:
 * 1. start the arms; time until every arm answers a ping on its control topic (its
 *    subscriptions made: the cluster makes one replicated JetStream consumer per QoS 1 one);
 * 2. a steady window: status rate per arm as a live subscriber sees it, CPU of the nodes, the
 *    simulators and the middlewares;
 * 3. SIGKILL the node leading MQTT's message stream; time until every arm answers again;
 *    restart the node;
 * 4. stop the arms: every state report each arm made must be one stored point (per arm).
 * A step fails when an arm never answers (180 s), or a count is off; stepping stops there.
 */
import fs from 'node:fs';
import path from 'node:path';
import mqtt from 'mqtt';
import { startNatsCluster, type NatsCluster } from '../tests/helpers/nats-cluster.ts';
import { armPinger } from './lib/arm-pinger.ts';
import { cpuMeter, sleep, until } from './lib/proc.ts';
import { round } from './lib/stats.ts';
import { agentResult, startAgent, startMiddleware, type Middleware } from './lib/stack.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const RATE_HZ = 50;
const ANSWER_MS = 180_000;

interface ClusterStep {
  arms: number;
  /** Seconds from starting the arms until every one answered a ping. */
  readyS: number;
  /** Status messages per arm per second a live subscriber saw in the window. */
  perArmHz: number;
  /** The reports in them (a message may join several), per arm per second. */
  reportsHz: number;
  cpuShare: { nodes: number; sims: number; middlewares: number };
  /** Seconds from the kill until every arm answered again. */
  recoveredS: number;
  published: number;
  stored: number;
  /** Arms whose stored count differs from their own: id → stored − published. */
  off: Record<string, number>;
  /** Of those stored more often: the spacing of each pair less than 1 ms apart, µs. */
  twiceUs: Record<string, number[]>;
  pass: boolean;
  why: string;
}

/** State reports stored per arm whose id starts with `prefix` (servo 000's `pwm` points). */
async function storedPerArm(url: string, db: string, prefix: string) {
  const q = `SELECT count("pwm") FROM "servo" WHERE "arm" =~ /^${prefix}/ AND "id" = '000' GROUP BY "arm"`;
  const res = await fetch(`${url}/query?db=${encodeURIComponent(db)}`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  }).catch(() => null);
  const out = new Map<string, number>();
  if (!res?.ok) return out;
  const body = (await res.json()) as {
    results?: { series?: { tags: { arm: string }; values: unknown[][] }[] }[];
  };
  for (const s of body.results?.[0]?.series ?? []) out.set(s.tags.arm, Number(s.values[0]![1]));
  return out;
}

/** Stored reports of `arm` less than 1 ms after the one before (a report stored twice), µs apart. */
async function closePairs(url: string, db: string, arm: string): Promise<number[]> {
  const q = `SELECT "pwm" FROM "servo" WHERE "arm" = '${arm}' AND "id" = '000'`;
  const res = await fetch(`${url}/query?db=${encodeURIComponent(db)}&epoch=u`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  }).catch(() => null);
  if (!res?.ok) return [];
  const body = (await res.json()) as { results?: { series?: { values: number[][] }[] }[] };
  const t = (body.results?.[0]?.series?.[0]?.values ?? []).map((v) => v[0]!);
  return t
    .slice(1)
    .map((x, i) => x - t[i]!)
    .filter((d) => d < 1000);
}

/** The node leading `$MQTT_msgs`, once it has one. */
async function streamLeader(c: NatsCluster): Promise<number> {
  await until(async () => (await c.stream('$MQTT_msgs')) !== null, 60_000, 200);
  const leader = (await c.stream('$MQTT_msgs'))?.leader;
  return c.nodes.findIndex((n) => n.name === leader);
}

async function runStep(
  ctx: Parameters<Section['run']>[0],
  arms: number,
  windowS: number,
): Promise<ClusterStep> {
  const prefix = `nats${arms}-`;
  const ids = Array.from({ length: arms }, (_, i) => `${prefix}${i + 1}`);
  const c = await startNatsCluster();
  const mws: Middleware[] = [];
  const pinger = armPinger(c.mqttUrls(2), `bench-cluster-ping-${arms}`);
  try {
    const first = await mqtt.connectAsync(c.nodes[0]!.mqttUrl, { clientId: `first-${arms}` });
    const leads = await streamLeader(c);
    await first.endAsync();
    for (const k of [0, 1])
      mws.push(
        await startMiddleware(
          {
            MQTT_URL: c.mqttUrls(k),
            NATS_URL: c.natsUrls(k),
            NATS_ACK_WAIT_MS: '5000',
            MQTT_CLIENT_ID: `bench-cluster-${arms}-${k}`,
            INFLUX_URL: ctx.influx.url,
            INFLUX_BUCKET: ctx.influx.bucket,
            SPOOL_DIR: fs.mkdtempSync(path.join(ctx.logDir, `spool-cluster-${arms}-${k}-`)),
            FLUSH_INTERVAL_MS: '1000',
          },
          path.join(ctx.logDir, `cluster-${arms}-middleware-${k}.log`),
        ),
      );
    // The shared consumer is there before the arms start (it takes what comes after it).
    const probe = await mqtt.connectAsync(c.nodes[2]!.mqttUrl, { clientId: `probe-${arms}` });
    await until(
      async () => {
        await probe.publishAsync('arm/probe/status', `$TIM:${Date.now()}!#000P1500!`, { qos: 1 });
        const m = await Promise.all(mws.map((x) => x.metrics()));
        return m.some((x) => (x['messages_total{topic="status"}'] ?? 0) > 0);
      },
      60_000,
      500,
    );
    await probe.endAsync();

    const countsFile = path.join(ctx.logDir, `cluster-${arms}-counts.json`);
    const lists = [0, 1, 2].map((k) => c.mqttUrls(k)).join(';');
    const t0 = Date.now();
    const agent = startAgent(
      'fleet',
      [lists, '1', String(arms), String(RATE_HZ), prefix, countsFile],
      path.join(ctx.logDir, `cluster-${arms}-sims.log`),
    );
    const fail = (why: string, extra: Partial<ClusterStep> = {}): ClusterStep => ({
      arms,
      readyS: NaN,
      perArmHz: NaN,
      reportsHz: NaN,
      cpuShare: { nodes: NaN, sims: NaN, middlewares: NaN },
      recoveredS: NaN,
      published: 0,
      stored: 0,
      off: {},
      twiceUs: {},
      ...extra,
      pass: false,
      why,
    });
    try {
      await agentResult<{ ready: number }>(agent, 60_000 + arms * 2000);
      const deaf = await pinger.untilAllAnswer(ids, ANSWER_MS);
      const readyS = round((Date.now() - t0) / 1000, 1);
      if (deaf.length > 0)
        return fail(`${deaf.length} of ${arms} arms not answering after ${ANSWER_MS / 1000} s`);
      ctx.log(`cluster: ${arms} arms answering after ${readyS} s`);

      const pids = [
        agent.pid,
        ...c.nodes.map((n) => n.process.pid ?? -1),
        ...mws.map((m) => m.child.pid),
      ];
      const meters = pids.map((p) => cpuMeter(p));
      for (const m of meters) m.start();
      const sum = (m: Map<string, number>) => ids.reduce((n, id) => n + (m.get(id) ?? 0), 0);
      const seen0 = sum(pinger.seen);
      const reports0 = sum(pinger.reports);
      await sleep(windowS * 1000);
      const shares = meters.map((m) => m.stop().share ?? NaN);
      const seen = sum(pinger.seen) - seen0;
      const reports = sum(pinger.reports) - reports0;
      const cpuShare = {
        sims: round(shares[0]!, 3),
        nodes: round(shares[1]! + shares[2]! + shares[3]!, 3),
        middlewares: round(shares[4]! + shares[5]!, 3),
      };
      const perArmHz = round(seen / arms / windowS, 1);
      const reportsHz = round(reports / arms / windowS, 1);

      const victim = c.nodes[leads]!;
      const killedAt = Date.now();
      await victim.process.kill();
      const lost = await pinger.untilAllAnswer(ids, ANSWER_MS);
      const recoveredS = round((Date.now() - killedAt) / 1000, 1);
      if (lost.length > 0)
        return fail(
          `${lost.length} of ${arms} arms not answering ${ANSWER_MS / 1000} s after the kill (${lost.slice(0, 5).join(', ')})`,
          {
            readyS,
            perArmHz,
            reportsHz,
            cpuShare,
          },
        );
      ctx.log(`cluster: ${arms} arms answering again ${recoveredS} s after the kill`);
      await victim.process.start();
      await until(async () => (await c.routes(leads)) === 2, 60_000, 500);
      await sleep(5000); // reports on every node again

      await agent.stop(30_000);
      const counts = JSON.parse(fs.readFileSync(countsFile, 'utf8')) as Record<string, number>;
      const published = Object.values(counts).reduce((a, b) => a + b, 0);
      let stored = new Map<string, number>();
      await until(
        async () => {
          stored = await storedPerArm(ctx.influx.url, ctx.influx.db, prefix);
          return ids.every((id) => stored.get(id) === counts[id]);
        },
        60_000,
        1000,
      );
      const off = Object.fromEntries(
        ids
          .filter((id) => stored.get(id) !== counts[id])
          .map((id) => [id, (stored.get(id) ?? 0) - counts[id]!]),
      );
      const total = [...stored.values()].reduce((a, b) => a + b, 0);
      const twiceUs: Record<string, number[]> = {};
      for (const id of Object.keys(off).filter((k) => off[k]! > 0))
        twiceUs[id] = await closePairs(ctx.influx.url, ctx.influx.db, id);
      const lossy = Object.values(off).filter((d) => d < 0).length;
      const twice = Object.values(off).filter((d) => d > 0).length;
      // Stepping stops at a loss; reports stored twice are counted and reported.
      const why = lossy > 0 ? `${lossy} arms lost reports` : '';
      const note = twice > 0 ? `${twice} arms had reports stored twice` : '';
      return {
        arms,
        readyS,
        perArmHz,
        reportsHz,
        cpuShare,
        recoveredS,
        published,
        stored: total,
        off,
        twiceUs,
        pass: !why,
        why: why || note,
      };
    } finally {
      await agent.stop(30_000);
    }
  } finally {
    await pinger.end().catch(() => {});
    for (const m of mws) await m.child.stop();
    await c.dispose();
  }
}

export const clusterSection: Section = {
  id: 'cluster',
  title: 'Cluster: N arms at 50 Hz on 3 NATS nodes, the stream leader killed mid-stream',
  async run(ctx): Promise<SectionOutput> {
    // BENCH_CLUSTER_ARMS=50 (or 25,50): only these steps.
    const only = process.env.BENCH_CLUSTER_ARMS?.split(',').map(Number);
    const counts = only?.length ? only : ctx.quick ? [6, 25, 50] : [6, 12, 25, 50, 100];
    const windowS = ctx.quick ? 10 : 20;
    const steps: ClusterStep[] = [];
    for (const arms of counts) {
      ctx.log(`cluster: ${arms} arms`);
      const step = await runStep(ctx, arms, windowS);
      steps.push(step);
      ctx.log(`cluster: ${arms} arms → ${step.why || 'ok'}`);
      if (!step.pass) break;
    }
    const best = steps.filter((s) => s.pass).at(-1);
    const twice = steps.filter((s) => Object.values(s.off).some((d) => d > 0)).map((s) => s.arms);
    const one = steps[0];
    const rows: Row[] = [
      {
        figure:
          'arms at 50 Hz answering and losing no report through a stream leader kill, highest step',
        value: best ? `${best.arms} (steps ${counts.join(', ')})` : 'none',
        baseline: one ? `${one.arms} arms: ${one.why || 'ok'}` : '—',
        target: '50 (issue 34 item 5)',
        met: (best?.arms ?? 0) >= 50,
      },
      {
        figure: 'steps with a report stored twice',
        value: twice.length ? twice.join(', ') : 'none',
        baseline: '—',
        target: 'none',
        met: twice.length === 0,
      },
      ...steps.map((s) => ({
        figure: `${s.arms} arms: answering after start / after the kill, s; reports / status messages per arm per s; CPU nodes/sims/middlewares`,
        value: `${fmt(s.readyS, 1)} / ${fmt(s.recoveredS, 1)}; ${fmt(s.reportsHz, 1)} / ${fmt(s.perArmHz, 1)} Hz; ${fmt(s.cpuShare.nodes)} / ${fmt(s.cpuShare.sims)} / ${fmt(s.cpuShare.middlewares)} cores`,
        baseline: `${s.stored} of ${s.published} reports stored${s.why ? `: ${s.why}` : ''}`,
        target: 'reported',
        met: null,
      })),
    ];
    return {
      rows,
      settings: { counts, windowS, rateHz: RATE_HZ, answerTimeoutS: ANSWER_MS / 1000 },
      data: { steps },
    };
  },
};
