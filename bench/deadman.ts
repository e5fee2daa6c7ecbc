/**
 * Section: the deadman. An operator holding `arm/{id}/operator` (will `0`, keep-alive
 * 2 s) starts a 10 s move of servo 000 and goes silent with its TCP connection open (a frozen
 * page; tests/helpers/raw-operator.ts). Figure: ms from its last packet to the simulator's
 * `$ERR:deadman stop!` when it beats as the HUD does (retained `1` every OPERATOR_BEAT_MS, the
 * controller's lease OPERATOR_LEASE_MS). Baseline: the same operator holding with a single `1`,
 * so only the broker's will can stop the arm: ms from its last packet to the will `0`. Both on
 * Mosquitto 2.0 (the bench's broker) and on the embedded Aedes broker (`armtwin broker`).
 * Silence comes right after a packet, the worst case for both.
 */
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { OPERATOR_BEAT_MS, OPERATOR_LEASE_MS } from '@armtwin/protocol';
import { rawOperator } from '../tests/helpers/raw-operator.ts';
import { startEmbeddedBroker, startSim } from './lib/stack.ts';
import { sleep, until } from './lib/proc.ts';
import { summarize, type Summary } from './lib/stats.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const KEEPALIVE_S = 2;
const BOUND_MS = 1.5 * KEEPALIVE_S * 1000;

/** Arrival times (epoch ms) of the stop and of the will, on one arm. */
class Watch {
  stops: number[] = [];
  wills: number[] = [];
  private constructor(readonly client: MqttClient) {}
  static async connect(url: string, arm: string): Promise<Watch> {
    const client = await mqtt.connectAsync(url, { clientId: `bench-deadman-watch-${arm}` });
    const w = new Watch(client);
    client.on('message', (topic, payload) => {
      const text = payload.toString('latin1');
      if (topic.endsWith('/status') && text.includes('$ERR:deadman stop!'))
        w.stops.push(Date.now());
      if (topic.endsWith('/operator') && text === '0') w.wills.push(Date.now());
    });
    await client.subscribeAsync([`arm/${arm}/status`, `arm/${arm}/operator`], { qos: 1 });
    return w;
  }
}

/** One drop: returns ms from the silence to the stop and to the will (NaN if none in 15 s). */
async function drop(
  url: string,
  port: number,
  arm: string,
  beat: boolean,
  watch: Watch,
  control: MqttClient,
): Promise<{ stopMs: number; willMs: number }> {
  const topic = `arm/${arm}/control`;
  await control.publishAsync(topic, '#000P500T800!', { qos: 1 });
  await sleep(1200);
  const op = await rawOperator({
    port,
    armId: arm,
    keepaliveS: KEEPALIVE_S,
    ...(beat ? { beatMs: OPERATOR_BEAT_MS } : {}),
  });
  await sleep(3 * OPERATOR_BEAT_MS);
  await control.publishAsync(topic, '#000P2500T9999!', { qos: 1 });
  await sleep(500);
  const stops0 = watch.stops.length;
  const wills0 = watch.wills.length;
  const silentAt = op.silence();
  await until(() => watch.wills.length > wills0, 15_000);
  if (beat) await until(() => watch.stops.length > stops0, 1000);
  op.close();
  const after = (list: number[], from: number) =>
    list.length > from ? list[from]! - silentAt : NaN;
  return { stopMs: after(watch.stops, stops0), willMs: after(watch.wills, wills0) };
}

async function measure(url: string, port: number, arm: string, reps: number, logFile: string) {
  const sim = await startSim(url, arm, 50, logFile);
  const watch = await Watch.connect(url, arm);
  const control = await mqtt.connectAsync(url, { clientId: `bench-deadman-ctl-${arm}` });
  const lease: number[] = [];
  const will: number[] = [];
  const willWithBeat: number[] = [];
  try {
    for (let i = 0; i < reps; i++) {
      const b = await drop(url, port, arm, true, watch, control);
      lease.push(b.stopMs);
      willWithBeat.push(b.willMs);
      const w = await drop(url, port, arm, false, watch, control);
      will.push(w.willMs);
    }
  } finally {
    await control.endAsync();
    await watch.client.endAsync();
    await sim.stop();
  }
  return {
    lease: summarize(lease),
    will: summarize(will),
    willWithBeat: summarize(willWithBeat),
    raw: { lease, will, willWithBeat },
  };
}

const ms = (s: Summary) => `p50 ${fmt(s.p50, 0)} ms, max ${fmt(s.max, 0)} ms (n = ${s.n})`;

export const deadmanSection: Section = {
  id: 'deadman',
  title: 'Deadman: operator silent → arm stopped, lease vs broker will',
  async run(ctx): Promise<SectionOutput> {
    const reps = ctx.quick ? 3 : 8;
    ctx.log(`deadman: ${reps} drops each way on Mosquitto`);
    const mosquitto = await measure(
      ctx.broker.url,
      ctx.broker.port,
      'bench-deadman-m',
      reps,
      path.join(ctx.logDir, 'deadman-sim-mosquitto.log'),
    );
    const aedes = await startEmbeddedBroker(path.join(ctx.logDir, 'deadman-aedes.log'));
    let embedded;
    try {
      ctx.log(`deadman: ${reps} drops each way on the embedded broker`);
      embedded = await measure(
        aedes.url,
        aedes.port,
        'bench-deadman-a',
        reps,
        path.join(ctx.logDir, 'deadman-sim-aedes.log'),
      );
    } finally {
      await aedes.child.stop();
    }
    const row = (broker: string, r: typeof mosquitto): Row => ({
      figure: `Deadman on ${broker}: silence → arm stopped (HUD beat, lease ${OPERATOR_LEASE_MS} ms)`,
      value: ms(r.lease),
      baseline: `will only: ${ms(r.will)}`,
      target: `≤ ${BOUND_MS} ms (1.5 × ${KEEPALIVE_S} s keep-alive)`,
      met: r.lease.n === reps && r.lease.max <= BOUND_MS,
    });
    return {
      rows: [row('Mosquitto 2.0', mosquitto), row('the embedded broker', embedded)],
      settings: {
        reps,
        keepaliveS: KEEPALIVE_S,
        beatMs: OPERATOR_BEAT_MS,
        leaseMs: OPERATOR_LEASE_MS,
        move: '#000P2500T9999! from 500 µs; silence 500 ms into it',
      },
      data: { mosquitto, embedded },
    };
  },
};
