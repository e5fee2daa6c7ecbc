/**
 * Smoke test for the real-services helper and the wire contract: a status payload sent with
 * the real `mosquitto_pub` through a throwaway Mosquitto reaches an mqtt.js subscriber (over
 * MQTT and over WebSockets, which the HUD uses) and decodes with the protocol reader.
 */
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import mqtt, { type IClientOptions, type MqttClient } from 'mqtt';
import { afterEach, describe, expect, test } from 'vitest';
import { createReader, type Frame, type Group, type ReaderError } from '@armtwin/protocol';
import { useMosquitto } from '../helpers/use-services.ts';

const run = promisify(execFile);
const TOPIC = 'arm/arm1/status';
const STAMP = 1_700_000_000_000;
const PAYLOAD = `$TIM:${STAMP}!{#000P1500!#001P1612!}#001T045V7400!`;

const broker = useMosquitto();
const clients: MqttClient[] = [];

afterEach(async () => {
  await Promise.all(clients.splice(0).map((c) => c.endAsync(true)));
});

async function connect(url: string, opts: IClientOptions = {}): Promise<MqttClient> {
  const client = await mqtt.connectAsync(url, {
    reconnectPeriod: 0,
    connectTimeout: 5000,
    ...opts,
  });
  clients.push(client);
  return client;
}

/** Resolves with the next message on `topic`; rejects if none comes within 10 s. */
function nextMessage(client: MqttClient, topic: string): Promise<Buffer> {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`no message on ${topic} within 10 s`)), 10_000);
    client.on('message', (t, payload) => {
      if (t !== topic) return;
      clearTimeout(timer);
      resolve(payload);
    });
  });
}

async function mosquittoPub(port: number, topic: string, message: string, qos = 0): Promise<void> {
  await run('mosquitto_pub', [
    '-h',
    '127.0.0.1',
    '-p',
    String(port),
    '-q',
    String(qos),
    '-t',
    topic,
    '-m',
    message,
  ]);
}

function decode(payload: Uint8Array) {
  const frames: Frame[] = [];
  const groups: Group[] = [];
  const errors: ReaderError[] = [];
  const reader = createReader({
    onFrame: (f) => frames.push(f),
    onGroup: (g) => groups.push(g),
    onError: (e) => errors.push(e),
  });
  reader.feed(payload);
  return { frames, groups, errors, bufferedBytes: reader.bufferedBytes };
}

describe('Mosquitto smoke', () => {
  test('a status payload from mosquitto_pub arrives over MQTT and decodes', async () => {
    const sub = await connect(broker().url);
    await sub.subscribeAsync(TOPIC, { qos: 0 });
    const received = nextMessage(sub, TOPIC);
    await mosquittoPub(broker().port, TOPIC, PAYLOAD);
    const payload = await received;

    expect(payload.toString('latin1')).toBe(PAYLOAD);
    const { frames, groups, errors, bufferedBytes } = decode(payload);
    expect(errors).toEqual([]);
    expect(bufferedBytes).toBe(0);
    expect(groups).toEqual([
      {
        type: 'group',
        frames: [
          { type: 'position', id: 0, pwm: 1500, time: STAMP },
          { type: 'position', id: 1, pwm: 1612, time: STAMP },
        ],
        invalid: 0,
        time: STAMP,
      },
    ]);
    expect(frames.filter((f) => f.type !== 'time')).toEqual([
      { type: 'health', id: 1, temp: 45, mv: 7400, time: STAMP },
    ]);
  });

  test('the WebSockets listener delivers what mosquitto_pub sends', async () => {
    const sub = await connect(broker().wsUrl);
    await sub.subscribeAsync('arm/+/status', { qos: 0 });
    const received = nextMessage(sub, TOPIC);
    await mosquittoPub(broker().port, TOPIC, PAYLOAD);
    expect((await received).toString('latin1')).toBe(PAYLOAD);
  });

  test('restart() keeps a persistent session and its queued QoS 1 message', async () => {
    const clientId = `smoke-persist-${process.pid}`;
    const session: IClientOptions = { clientId, clean: false };
    const first = await connect(broker().url, session);
    await first.subscribeAsync('arm/arm1/control', { qos: 1 });
    await first.endAsync();

    await mosquittoPub(broker().port, 'arm/arm1/control', '#000P1500T1000!', 1);
    await broker().restart();

    // Listen before CONNACK: the queued message is delivered right after it.
    const again = mqtt.connect(broker().url, { ...session, reconnectPeriod: 0 });
    clients.push(again);
    const received = await nextMessage(again, 'arm/arm1/control');
    expect(received.toString('latin1')).toBe('#000P1500T1000!');
  });
});
