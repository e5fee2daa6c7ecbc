/**
 * A part's QoS 1 messages survive a broker that closes the connection while mqtt.js re-sends its
 * store (packages/link/src/republish.ts, mqttjs/MQTT.js#2015). This is what a NATS node does when
 * its stream leader is lost (docs/cluster.md § Found on the cluster): it holds the first re-sent
 * message while JetStream fails to store it, then closes the connection.
 *
 * Real broker (the embedded Aedes), real mqtt.js through `connectBrokers`. The broker is made to
 * act as that NATS node. For the publisher's first two connections it holds each publish
 * without a PUBACK, then refuses it, which closes the connection. Messages are published:
 * - on the first connection (they are stored unacknowledged and re-sent);
 * - while the second connection re-sends them (they wait in mqtt.js's queue, and mqtt.js alone
 *   would drop them on the close).
 * The third connection lets everything through: a subscriber gets every message.
 */
import mqtt from 'mqtt';
import { afterAll, expect, test } from 'vitest';
import { startBroker, type Broker } from '@armtwin/broker';
import { connectBrokers, type BrokerClient } from '@armtwin/link';

let broker: Broker | undefined;
let pub: BrokerClient | undefined;
let sub: mqtt.MqttClient | undefined;
afterAll(async () => {
  await pub?.endAsync(true);
  await sub?.endAsync(true);
  await broker?.close();
});

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));
async function until(fn: () => boolean, ms: number, what: string) {
  const deadline = Date.now() + ms;
  while (!fn()) {
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await sleep(20);
  }
}

test('QoS 1 messages published while the store is re-sent survive the connection closing', async () => {
  broker = await startBroker({ port: 0 });
  const aedes = broker.aedes;
  let connections = 0;
  let held = 0;
  aedes.on('client', (c) => c.id === 'pub' && connections++);
  const allow = aedes.authorizePublish!.bind(aedes);
  aedes.authorizePublish = (client, packet, done) => {
    if (client?.id !== 'pub' || connections > 2) return allow(client, packet, done);
    held++;
    // The node's store request times out: no PUBACK, the connection is closed.
    setTimeout(() => done(new Error('store timed out')), 400);
  };

  sub = await mqtt.connectAsync(broker.url, { clientId: 'sub' });
  const got = new Set<string>();
  sub.on('message', (_t, p) => got.add(p.toString()));
  await sub.subscribeAsync('arm/t/status', { qos: 1 });

  pub = connectBrokers([broker.url], { clientId: 'pub', reconnectPeriod: 100 });
  const dropped: string[] = [];
  const send = (m: string) =>
    pub!.publish('arm/t/status', m, { qos: 1 }, (err) => err && dropped.push(m));
  await until(() => pub!.connected, 5000, 'the first connection');
  for (let i = 1; i <= 3; i++) send(`first-${i}`);
  // The second connection re-sends the store, its first message held by the broker.
  await until(() => connections === 2 && held > 3, 5000, 'the store re-sent');
  for (let i = 1; i <= 5; i++) send(`during-${i}`);

  const all = [1, 2, 3].map((i) => `first-${i}`).concat([1, 2, 3, 4, 5].map((i) => `during-${i}`));
  await until(() => all.every((m) => got.has(m)), 10_000, 'every message at the subscriber').catch(
    (err: Error) => {
      throw new Error(`${err.message}: got ${[...got].join(' ')}; connections ${connections}`);
    },
  );
  expect(connections).toBeGreaterThanOrEqual(3);
  expect(dropped).toEqual([]);
});
