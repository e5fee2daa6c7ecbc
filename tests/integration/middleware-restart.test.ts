/**
 * "Nothing is lost across a middleware restart": QoS 1 publishes, the middleware
 * SIGKILLed mid-stream and started again with the same client id and spool: InfluxDB ends
 * with exactly N points (the broker queued what arrived meanwhile; redelivered messages
 * carry the same $TIM, so rewriting them overwrites identical points).
 */
import fs from 'node:fs';
import { expect, test } from 'vitest';
import { freePort } from '../helpers/ports.ts';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import {
  countPoints,
  startPublisher,
  statePayloads,
  waitForValue,
} from '../../apps/middleware/test/support/harness.ts';

// Mosquitto queues at most 1000 messages per offline session by default.
const broker = useMosquitto({ extraConfig: ['max_queued_messages 100000'] });
const influx = useInflux();
const mws = useMiddlewares('mw-restart', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

test(
  'middleware SIGKILLed mid-stream and restarted: still exactly N points (QoS 1)',
  { timeout: 90_000 },
  async () => {
    const port = await freePort();
    const env = {
      FLUSH_INTERVAL_MS: '1000', // a full open batch is in flight when the kill comes
      BATCH_SIZE: '100000',
    };
    let mw = await mws.spawn({ env, port });
    const inf = { url: influx().url, db: influx().db };
    const n = 3000;
    const messages = statePayloads(n, 6, Date.UTC(2026, 2, 1));
    const pub = startPublisher(broker().port, 'arm/arm1/status', 1);
    const sending = pub.send(messages, 20, 20); // ~1000 messages/s
    await sleep(1500);
    await mw.kill();
    const atKill = await countPoints(inf, 'servo', 'pwm');
    await sleep(1000);
    mw = await mws.spawn({ env, port }); // the same client id, spool and log
    await sending;
    expect(await pub.end()).toBe(0);

    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), 6 * n, 30_000)).toBe(6 * n);
    expect(atKill).toBeLessThan(6 * n); // the kill really was mid-stream
    expect((await mw.metrics())['points_dropped_total']).toBe(0);
    expect(fs.readFileSync(mws.log(), 'utf8')).toMatch(/replaying/);
  },
);
