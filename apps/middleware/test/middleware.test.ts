import { EventEmitter } from 'node:events';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import { pino } from 'pino';
import { describe, expect, test } from 'vitest';
import { loadConfig } from '../src/config.ts';
import type { InfluxWriter } from '../src/influx.ts';
import { startMiddleware } from '../src/index.ts';
import { subscriptionTopics } from '../src/mqtt.ts';

/** Just enough of an mqtt.js client: emits what the broker would, records subscriptions. */
class FakeClient extends EventEmitter {
  subscribed: string[] = [];
  options: unknown;
  handleMessage = (_p: unknown, done: () => void) => done();
  subscribe(topics: string[], _o: unknown, cb: (e: Error | null) => void) {
    this.subscribed.push(...topics);
    cb(null);
  }
  end(_force: boolean, _o: unknown, cb: () => void) {
    cb();
  }
  /** Delivers a message the way mqtt.js does: 'message', then handleMessage → (PUBACK). */
  deliver(topic: string, payload: string): Promise<void> {
    this.emit('message', topic, Buffer.from(payload), {});
    return new Promise((resolve) => this.handleMessage({}, resolve));
  }
}

const silent = pino({ level: 'silent' });

async function run(env: Record<string, string>, writer?: InfluxWriter) {
  const client = new FakeClient();
  const config = loadConfig({ PORT: '0', ...env });
  const mw = await startMiddleware(config, {
    logger: silent,
    connect: (_url, opts) => ((client.options = opts), client as unknown as MqttClient),
    writer,
    listen: false,
  });
  client.emit('connect');
  return { client, mw };
}

describe('startMiddleware', () => {
  test('subscribes with a persistent session, fixed client id, configured QoS; shared group when set', async () => {
    const { client, mw } = await run({ MQTT_CLIENT_ID: 'x1', MQTT_SHARE_GROUP: 'armtwin' });
    expect(client.options).toMatchObject({
      clientId: 'x1',
      clean: false,
      keepalive: 60,
      reconnectPeriod: 1000,
    });
    expect(client.subscribed).toEqual([
      '$share/armtwin/arm/+/status',
      '$share/armtwin/arm/+/control',
      '$share/armtwin/arm/+/control/+',
      '$share/armtwin/arm/+/audit',
      '$share/armtwin/arm/+/profile',
    ]);
    expect(subscriptionTopics('')).toEqual([
      'arm/+/status',
      'arm/+/control',
      'arm/+/control/+',
      'arm/+/audit',
      'arm/+/profile',
    ]);
    await mw.stop();
  });

  test('without INFLUX_URL it runs, counts frames, and says storage: false', async () => {
    const { client, mw } = await run({});
    await client.deliver('arm/arm1/status', '#000P1500!junk');
    const h = mw.health();
    expect(h).toMatchObject({ ok: true, storage: false, mqtt: { connected: true } });
    expect(mw.metrics.frames.position).toBe(1);
    await mw.stop();
  });

  test('batch mode: a message is in the spool before it is acknowledged; stop writes it', async () => {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-mw-test-'));
    const bodies: string[] = [];
    const writer: InfluxWriter = {
      write: async (b) => void bodies.push(b),
      ping: async () => true,
      ensureBucket: async () => 'ok',
    };
    const { client, mw } = await run(
      { SPOOL_DIR: dir, FLUSH_INTERVAL_MS: '60000', INFLUX_CREATE_BUCKET: 'false' },
      writer,
    );
    await client.deliver('arm/arm1/status', '$TIM:1000!#000P1500!#001P2500!');
    const [folder] = fs.readdirSync(dir); // this destination's folder (src/spool-target.ts)
    expect(fs.readFileSync(path.join(dir, folder!, 'journal.lp'), 'utf8')).toBe(
      'servo,arm=arm1,id=000 pwm=1500i,angle=0 1000000\nservo,arm=arm1,id=001 pwm=2500i,angle=135 1000000\n',
    );
    expect(bodies).toEqual([]);
    await mw.stop();
    expect(bodies.join('').split('\n').filter(Boolean)).toHaveLength(2);
    expect(mw.metrics.pointsWritten).toBe(2);
    fs.rmSync(dir, { recursive: true });
  });

  test('a full spool pauses intake (the acknowledgement waits) until it drains', async () => {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-mw-test-'));
    let up = false;
    const writer: InfluxWriter = {
      write: async () => {
        if (!up) throw new Error('ECONNREFUSED');
      },
      ping: async () => up,
      ensureBucket: async () => 'ok',
    };
    const { client, mw } = await run(
      {
        SPOOL_DIR: dir,
        SPOOL_MAX_BYTES: '1024',
        BATCH_SIZE: '5',
        MIN_RETRY_DELAY_MS: '20',
        MAX_RETRY_DELAY_MS: '40',
        INFLUX_CREATE_BUCKET: 'false',
      },
      writer,
    );
    let t = 1000;
    let pending: Promise<void> = Promise.resolve();
    while (!mw.metrics.spoolFull) {
      await pending;
      pending = client.deliver('arm/arm1/status', `$TIM:${t++}!{#000P1500!#001P1500!#002P1500!}`);
    }
    let acked = false;
    void pending.then(() => (acked = true));
    await new Promise((r) => setTimeout(r, 200));
    expect(acked).toBe(false);
    expect(mw.health()).toMatchObject({ ok: false, spool: { full: true } });
    up = true;
    await pending;
    expect(mw.metrics.spoolFullEvents).toBe(1);
    await mw.flush(5000);
    expect(mw.metrics.pointsWritten).toBe(mw.metrics.pointsProduced);
    expect(mw.metrics.pointsDropped).toBe(0);
    await mw.stop();
    fs.rmSync(dir, { recursive: true });
  });
});

describe('several brokers (docs/protocol.md § Several brokers)', () => {
  test('connected to every broker at once: takes in from each; the broker in use is the first connected', async () => {
    const clients = new Map<string, FakeClient>();
    const mw = await startMiddleware(
      loadConfig({ PORT: '0', MQTT_URL: 'mqtt://lan:1883,mqtt://remote:1883' }),
      {
        logger: silent,
        connect: (url, opts) => {
          const c = new FakeClient();
          c.options = opts;
          clients.set(url, c);
          return c as unknown as MqttClient;
        },
        listen: false,
      },
    );
    const lan = clients.get('mqtt://lan:1883')!;
    const remote = clients.get('mqtt://remote:1883')!;
    expect(remote.options).toEqual(lan.options); // the same persistent session on each
    lan.emit('connect');
    remote.emit('connect');
    // Subscribed on both, the same session; what a publisher sends on the fall-back is stored.
    expect(lan.subscribed).toEqual(remote.subscribed);
    expect(lan.subscribed).toContain('arm/+/status');
    await remote.deliver('arm/arm1/status', '#000P1500!');
    await lan.deliver('arm/arm1/status', '#000P1510!');
    expect(mw.metrics.frames.position).toBe(2);
    expect(mw.health().mqtt).toMatchObject({
      connected: true,
      broker: 'Broker 1 of 2: mqtt://lan:1883',
    });
    // The first lost: the second, already connected, is the one in use (a move); then back.
    lan.emit('close');
    expect(mw.health().mqtt).toMatchObject({
      connected: true,
      broker: 'Broker 2 of 2: mqtt://remote:1883',
    });
    expect(mw.metrics.mqttBrokerMoves).toBe(1);
    lan.emit('connect');
    expect(mw.health().mqtt.broker).toBe('Broker 1 of 2: mqtt://lan:1883');
    expect(mw.metrics.mqttBrokerMoves).toBe(2);
    // None left: not connected.
    lan.emit('close');
    remote.emit('close');
    expect(mw.health().mqtt.connected).toBe(false);
    await mw.stop();
  });
});
