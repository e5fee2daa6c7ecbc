/**
 * A probe of the first broker (packages/link/src/probe.ts, docs/protocol.md § Several brokers) on a
 * real Mosquitto. A probe made with a part's own client id and persistent session (as the
 * middleware's were: `onProbeConnected` subscribes there) is sent, right behind the CONNACK,
 * what the broker has queued for that session. It must acknowledge none of it: every message
 * queued for the session reaches the part's own connection when it comes back. (Probes that
 * acknowledged what arrived before their 'connect' event lost state reports in the two-broker
 * failover run, tests/integration/brokers-failover.test.ts: 162 of 200 here.)
 */
import mqtt, { type IClientOptions } from 'mqtt';
import { expect, test } from 'vitest';
import { probeBroker } from '@armtwin/link';
import { useMosquitto } from '../helpers/use-services.ts';

const broker = useMosquitto();
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
const N = 200;

test('probes of a persistent session acknowledge nothing: all that was queued reaches the part', async () => {
  const url = broker().url;
  const session: IClientOptions = {
    clientId: 'probe-session',
    clean: false,
    protocolVersion: 4,
    reconnectPeriod: 0,
  };
  // The session exists, subscribed at QoS 1, and its client is away.
  const away = await mqtt.connectAsync(url, session);
  await away.subscribeAsync('arm/+/status', { qos: 1 });
  await away.endAsync();
  // N reports are published meanwhile: the broker queues them for the session.
  const pub = await mqtt.connectAsync(url, { clientId: 'probe-publisher' });
  for (let i = 0; i < N; i++) await pub.publishAsync('arm/p1/status', `report ${i}`, { qos: 1 });
  await pub.endAsync();

  // Three probes, as the middleware's: subscribe, done at the SUBACK or at a delivered message.
  for (let k = 0; k < 3; k++) {
    const ok = await probeBroker(
      (u, o) => mqtt.connect(u, o),
      url,
      session,
      5000,
      (probe, held) =>
        new Promise<void>((resolve, reject) => {
          void held.then(resolve);
          probe.subscribe('arm/+/status', { qos: 1 }, (err) => (err ? reject(err) : resolve()));
        }),
    );
    expect(ok).toBe(true);
  }

  // The part itself comes back: every queued report is delivered to it.
  const got = new Set<string>();
  const back = mqtt.connect(url, session);
  back.on('message', (_topic, payload) => got.add(String(payload)));
  const deadline = Date.now() + 15_000;
  while (got.size < N && Date.now() < deadline) await sleep(100);
  await back.endAsync();
  expect(got.size).toBe(N);
});
