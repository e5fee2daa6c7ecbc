/**
 * The batched journal keeps the spool's promise: a QoS 1 message is acknowledged only once its
 * points are in the journal. The real mqtt.js client (and the real middleware, spool and file)
 * against a scripted broker on an in-memory stream, which reads the journal at the moment each
 * PUBACK reaches it. A burst of messages arrives in one chunk, as from a busy broker, so their
 * points share one journal write.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { Duplex } from 'node:stream';
import { MqttClient } from 'mqtt';
import { pino } from 'pino';
import { afterEach, expect, test } from 'vitest';
import { loadConfig } from '../src/config.ts';
import type { InfluxWriter } from '../src/influx.ts';
import { startMiddleware } from '../src/index.ts';

const dirs: string[] = [];
afterEach(() => {
  for (const d of dirs.splice(0)) fs.rmSync(d, { recursive: true, force: true });
});

/** An MQTT 3.1.1 packet: type/flags byte, remaining length, body. */
function packet(first: number, body: Buffer): Buffer {
  const len: number[] = [];
  let n = body.length;
  do {
    let b = n % 128;
    n = Math.floor(n / 128);
    if (n > 0) b |= 128;
    len.push(b);
  } while (n > 0);
  return Buffer.concat([Buffer.from([first, ...len]), body]);
}
const u16 = (v: number) => Buffer.from([v >> 8, v & 255]);
const str = (s: string) => Buffer.concat([u16(Buffer.byteLength(s)), Buffer.from(s)]);
const publish = (topic: string, id: number, payload: string) =>
  packet(0x32, Buffer.concat([str(topic), u16(id), Buffer.from(payload)]));

/** A broker that answers CONNECT and SUBSCRIBE and hands each PUBACK's id to `onPuback`. */
function scriptedBroker(onSubscribed: () => void, onPuback: (id: number) => void): Duplex {
  let buf = Buffer.alloc(0);
  const broker: Duplex = new Duplex({
    read() {},
    write(chunk: Buffer, _enc, done) {
      buf = Buffer.concat([buf, chunk]);
      for (;;) {
        let len = 0;
        let mul = 1;
        let i = 1;
        for (; i < buf.length; i++) {
          len += (buf[i]! & 127) * mul;
          mul *= 128;
          if (!(buf[i]! & 128)) break;
        }
        if (i >= buf.length || buf.length < i + 1 + len) break;
        const type = buf[0]! >> 4;
        const body = buf.subarray(i + 1, i + 1 + len);
        buf = buf.subarray(i + 1 + len);
        if (type === 1) broker.push(Buffer.from([0x20, 2, 0, 0])); // CONNACK
        if (type === 8) {
          // SUBACK: QoS 1 granted to every filter (count the filters: length, name, options)
          let filters = 0;
          for (let j = 2; j < body.length; j += 2 + body.readUInt16BE(j) + 1) filters++;
          broker.push(packet(0x90, Buffer.concat([body.subarray(0, 2), Buffer.alloc(filters, 1)])));
          setImmediate(onSubscribed);
        }
        if (type === 4) onPuback(body.readUInt16BE(0));
        if (type === 12) broker.push(Buffer.from([0xd0, 0])); // PINGRESP
      }
      done();
    },
  });
  return broker;
}

test('a burst of QoS 1 messages: every PUBACK leaves after its points are in the journal', async () => {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-ack-test-'));
  dirs.push(dir);
  const writer: InfluxWriter = {
    write: async () => {},
    ping: async () => true,
    ensureBucket: async () => 'ok',
  };
  const N = 200;
  const pointsAtAck = new Map<number, number>();
  const journal = () => {
    const [folder] = fs.readdirSync(dir);
    const file = path.join(dir, folder!, 'journal.lp');
    return fs.existsSync(file) ? fs.readFileSync(file, 'latin1') : '';
  };
  let broker!: Duplex;
  const subscribed = new Promise<void>((resolve) => {
    broker = scriptedBroker(resolve, (id) => {
      const text = journal();
      // the points of message `id` (stamp 1000 + id, in µs) are on file when its PUBACK leaves
      pointsAtAck.set(id, text.split(` ${(1000 + id) * 1000}\n`).length - 1);
    });
  });
  const config = loadConfig({
    PORT: '0',
    SPOOL_DIR: dir,
    FLUSH_INTERVAL_MS: '60000',
    BATCH_SIZE: '100000',
    INFLUX_CREATE_BUCKET: 'false',
    MQTT_QOS: '1',
  });
  const mw = await startMiddleware(config, {
    logger: pino({ level: 'silent' }),
    connect: (_url, opts) => new MqttClient(() => broker, { ...opts, reconnectPeriod: 0 }),
    writer,
    listen: false,
  });
  await subscribed;
  const group = '{#000P1500!#001P1600!#002P1700!#003P1800!#004P1900!#005P2000!}';
  const burst = Array.from({ length: N }, (_, k) =>
    publish('arm/a1/status', k + 1, `$TIM:${1000 + k + 1}!${group}`),
  );
  broker.push(Buffer.concat(burst)); // one chunk, as a busy broker's socket read brings them
  const t0 = Date.now();
  while (pointsAtAck.size < N && Date.now() - t0 < 10_000)
    await new Promise((r) => setTimeout(r, 10));
  expect(pointsAtAck.size).toBe(N);
  expect([...pointsAtAck.values()].every((n) => n === 6)).toBe(true);
  expect(journal().split('\n').filter(Boolean)).toHaveLength(6 * N);
  expect(mw.metrics.pointsProduced).toBe(6 * N);
  await mw.stop();
});
