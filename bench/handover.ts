/**
 * Section: control hand-over (issue 18). On the bench's Mosquitto, `armtwin sim` keeps who holds
 * the arm (docs/protocol.md § Control). Alice holds it; bob asks; the figure is the time from
 * alice's `grant bob` leaving her client to the retained holder record naming bob arriving at a
 * third client, then bob releases and alice takes it back (the take timed the same way).
 * Baseline: the broker alone, the same three clients: a message from alice's client to the third
 * client (what any hand-over costs at least).
 */
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import { connectMqtt, startSim } from './lib/stack.ts';
import { until } from './lib/proc.ts';
import { summarize, type Summary } from './lib/stats.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const ARM = 'bench-handover';

/** The holder records and echo messages the watcher got, with arrival times (epoch ms). */
class Watch {
  holder: { user: string | null; requests: string[] } = { user: null, requests: [] };
  holderAt = 0;
  echoAt = new Map<string, number>();
  feed(topic: string, text: string): void {
    const at = performance.now();
    if (topic.endsWith('/holder')) {
      this.holder = JSON.parse(text) as Watch['holder'];
      this.holderAt = at;
    } else this.echoAt.set(text, at);
  }
}

const ms = (s: Summary) => `${fmt(s.p50, 1)} / ${fmt(s.p99, 1)} ms`;

async function timed(send: () => Promise<unknown>, done: () => boolean): Promise<number> {
  const t0 = performance.now();
  await send();
  if (!(await until(async () => done(), 5000, 1))) return NaN;
  return performance.now() - t0;
}

export const handoverSection: Section = {
  id: 'handover',
  title: 'Control hand-over: grant → the new holder, at a subscriber',
  async run(ctx): Promise<SectionOutput> {
    const n = ctx.quick ? 10 : 40;
    const url = ctx.broker.url;
    const sim = await startSim(url, ARM, 50, path.join(ctx.logDir, 'handover-sim.log'));
    const clients: MqttClient[] = [];
    try {
      const [alice, bob, watcher] = await Promise.all(
        ['alice', 'bob', 'watch'].map((n) =>
          connectMqtt(url, `bench-handover-${n}-${process.pid}`),
        ),
      );
      clients.push(alice!, bob!, watcher!);
      const w = new Watch();
      watcher!.on('message', (topic, payload) => w.feed(topic, payload.toString('utf8')));
      await watcher!.subscribeAsync([`arm/${ARM}/holder`, `bench/${ARM}/echo`], { qos: 1 });
      const claim = (c: MqttClient, who: string, words: string) =>
        c.publishAsync(`arm/${ARM}/claim/${who}`, words, { qos: 1 });
      const grants: number[] = [];
      const takes: number[] = [];
      const echoes: number[] = [];
      await claim(alice!, 'alice', 'take');
      if (!(await until(async () => w.holder.user === 'alice', 5000, 5)))
        throw new Error('the sim never named alice as the holder');
      for (let k = 0; k < n; k++) {
        await claim(bob!, 'bob', 'ask');
        await until(async () => w.holder.requests.includes('bob'), 5000, 1);
        grants.push(
          await timed(
            () => claim(alice!, 'alice', 'grant bob'),
            () => w.holder.user === 'bob',
          ),
        );
        await claim(bob!, 'bob', 'release');
        await until(async () => w.holder.user === null, 5000, 1);
        takes.push(
          await timed(
            () => claim(alice!, 'alice', 'take'),
            () => w.holder.user === 'alice',
          ),
        );
        const tag = `e${k}`;
        echoes.push(
          await timed(
            () => alice!.publishAsync(`bench/${ARM}/echo`, tag, { qos: 1 }),
            () => w.echoAt.has(tag),
          ),
        );
      }
      const g = summarize(grants.filter(Number.isFinite));
      const t = summarize(takes.filter(Number.isFinite));
      const e = summarize(echoes.filter(Number.isFinite));
      const rows: Row[] = [
        {
          figure: 'Control hand-over: `grant` → the holder record naming the new holder, p50 / p99',
          value: `${ms(g)} (n = ${g.n})`,
          baseline: `the broker alone, one message client → client: ${ms(e)}`,
          target: 'reported',
          met: null,
        },
        {
          figure: 'Control taken when nobody holds it: `take` → the holder record, p50 / p99',
          value: `${ms(t)} (n = ${t.n})`,
          baseline: `the broker alone: ${ms(e)}`,
          target: 'reported',
          met: null,
        },
      ];
      return {
        rows,
        settings: { n, broker: 'Mosquitto (the bench broker)', qos: 1 },
        data: { grantMs: g, takeMs: t, brokerMs: e },
      };
    } finally {
      await Promise.all(clients.map((c) => c.endAsync().catch(() => {})));
      await sim.stop();
    }
  },
};
