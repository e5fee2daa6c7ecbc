/**
 * Section `foxglove` (issue 33): `armtwin up --foxglove --rate 250` (6 servos × 250 Hz), and
 * 1. the latency from an arm's report (its `$TIM` stamp, the sim's clock on this machine) to a
 *    Foxglove client's joint states (npm FoxgloveClient, foxglove.websocket.v1), beside the HUD's
 *    path to the same reports (mqtt.js over WebSockets at /mqtt), both in this process at once;
 * 2. the CPU of the `up` process (broker, sim, Foxglove server) with no Foxglove client and with
 *    N clients each subscribed to `/arm/joint_states` and `/arm/tf` (what a 3D panel reads):
 *    (CPU(N) − CPU(0)) ÷ N is the server's CPU per connected client.
 */
import mqtt from 'mqtt';
import WebSocket from 'ws';
import { FoxgloveClient } from '@armtwin/foxglove/ws-protocol';
import { freePorts } from '../tests/helpers/services.ts';
import { ARMTWIN, startUpProcess } from '../tests/integration/sim-helpers.ts';
import { cpuMeter, sleep } from './lib/proc.ts';
import { round, summarize } from './lib/stats.ts';
import { fmt, type Row, type Section, type SectionOutput } from './lib/types.ts';

const ARM = 'arm1';

/** A FoxgloveClient subscribed to `topics`; `onMessage(topic, ns)` per message. */
function foxClient(url: string, topics: string[], onMessage: (topic: string, ns: bigint) => void) {
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const client = new FoxgloveClient({ ws: ws as never });
  const subs = new Map<number, string>();
  client.on('advertise', (channels) => {
    for (const c of channels)
      if (topics.includes(c.topic)) subs.set(client.subscribe(c.id), c.topic);
  });
  client.on('message', (m) => onMessage(subs.get(m.subscriptionId) ?? '', m.timestamp));
  return client;
}

export const foxgloveSection: Section = {
  id: 'foxglove',
  title: 'Foxglove live: report → client latency beside the HUD’s, server CPU per client at 250 Hz',
  async run(ctx): Promise<SectionOutput> {
    const windowS = ctx.quick ? 10 : 30;
    const clientsN = ctx.quick ? 4 : 8;
    const [httpPort = 0, mqttPort = 0, foxPort = 0] = await freePorts(3);
    const up = await startUpProcess(
      [ARMTWIN, 'up'],
      ['--no-middleware', '--no-web', '--rate', '250', '--foxglove', String(foxPort)],
      { httpPort, mqttPort },
    );
    const url = `ws://127.0.0.1:${foxPort}`;
    const stateTopic = `/${ARM}/joint_states`;
    try {
      // 1. latency, both paths at once
      const hudMs: number[] = [];
      const foxMs: number[] = [];
      let measuring = false;
      const hud = await mqtt.connectAsync(`ws://127.0.0.1:${httpPort}/mqtt`);
      hud.on('message', (_t, payload) => {
        const m = /^\$TIM:(\d+)!/.exec(payload.toString('latin1'));
        if (measuring && m) hudMs.push(Date.now() - Number(m[1]));
      });
      await hud.subscribeAsync(`arm/${ARM}/status`, { qos: 0 });
      const fox = foxClient(url, [stateTopic], (t, ns) => {
        if (measuring && t === stateTopic) foxMs.push(Date.now() - Number(ns / 1_000_000n));
      });
      await sleep(2000);
      ctx.log(`foxglove: latency, ${windowS} s at 250 Hz, HUD path and Foxglove client together`);
      measuring = true;
      await sleep(windowS * 1000);
      measuring = false;
      fox.close();
      await hud.endAsync();
      const hudS = summarize(hudMs);
      const foxS = summarize(foxMs);

      // 2. CPU of up with 0 and with N Foxglove clients
      const meter = cpuMeter(up.proc.pid!);
      await sleep(1000);
      meter.start();
      await sleep(windowS * 1000);
      const idle = meter.stop();
      let received = 0;
      const clients = Array.from({ length: clientsN }, () =>
        foxClient(url, [stateTopic, `/${ARM}/tf`], () => received++),
      );
      await sleep(2000);
      ctx.log(`foxglove: CPU of up with ${clientsN} clients, ${windowS} s`);
      const r0 = received;
      meter.start();
      await sleep(windowS * 1000);
      const busy = meter.stop();
      const perClientMsgs = (received - r0) / clientsN / busy.wallS;
      for (const c of clients) c.close();
      const perClient = (busy.share - idle.share) / clientsN;

      const ms = (v: number) => `${fmt(v, 2)} ms`;
      const rows: Row[] = [
        {
          figure: 'Report → client latency p50 / p99: Foxglove client (joint states)',
          value: `${ms(foxS.p50)} / ${ms(foxS.p99)} (${foxS.n} messages)`,
          baseline: `HUD path (mqtt.js over WebSockets) ${ms(hudS.p50)} / ${ms(hudS.p99)} (${hudS.n})`,
          target: 'reported',
          met: null,
        },
        {
          figure: 'Added latency of the Foxglove path, p50',
          value: ms(foxS.p50 - hudS.p50),
          baseline: '0 (the HUD path)',
          target: 'reported',
          met: null,
        },
        {
          figure: `Server CPU per connected client (share of one core), 250 Hz, ${clientsN} clients`,
          value: `${fmt(perClient * 100, 2)} % (${fmt(perClientMsgs, 0)} messages/s each)`,
          baseline: `up with no Foxglove client ${fmt(idle.share * 100, 1)} %, with ${clientsN}: ${fmt(busy.share * 100, 1)} %`,
          target: 'reported',
          met: null,
        },
      ];
      return {
        rows,
        settings: {
          rateHz: 250,
          servos: 6,
          windowS,
          clients: clientsN,
          subprotocol: 'foxglove.websocket.v1',
        },
        data: {
          foxglove: foxS,
          hud: hudS,
          cpuIdleShare: round(idle.share, 4),
          cpuBusyShare: round(busy.share, 4),
          cpuPerClientShare: round(perClient, 5),
          messagesPerClientPerS: round(perClientMsgs, 1),
        },
      };
    } finally {
      await up.stop();
    }
  },
};
