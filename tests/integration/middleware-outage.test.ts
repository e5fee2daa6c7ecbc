/**
 * "Nothing is lost while InfluxDB is down": influxd stopped for 30 s in the middle of
 * a stream, then started again: the middleware spools, retries with back-off, replays, and
 * InfluxDB ends with exactly N points.
 */
import { expect, test } from 'vitest';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import {
  countPoints,
  startPublisher,
  statePayloads,
  waitForValue,
} from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-outage', () => ({ mqttUrl: broker().url, influx: influx() }));
const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

test(
  'influxd stopped 30 s mid-stream, then restarted: still exactly N points',
  { timeout: 120_000 },
  async () => {
    const mw = await mws.spawn({
      env: {
        FLUSH_INTERVAL_MS: '250',
        BATCH_SIZE: '300',
        MIN_RETRY_DELAY_MS: '250',
        MAX_RETRY_DELAY_MS: '2000',
      },
    });
    const inf = { url: influx().url, db: influx().db };
    const messages = statePayloads(3600, 6, Date.UTC(2026, 1, 1)); // 21 600 points
    const pub = startPublisher(broker().port, 'arm/arm1/status', 1);
    // 100 messages/s (600 points/s) for 36 s; influxd goes away from ~3 s to ~33 s
    const sending = pub.send(messages, 10, 100);
    await sleep(3000);
    await influx().stop();
    await sleep(10_000);
    const during = await mw.metrics();
    expect(during['spool_files']).toBeGreaterThan(0);
    expect(during['write_batches_total{result="failed"}']).toBeGreaterThan(0);
    const health = await mw.health();
    expect(health.status).toBe(503);
    expect(health.body).toMatchObject({ influx: { reachable: false }, mqtt: { connected: true } });
    await sleep(20_000);
    await influx().start();
    await sending;
    expect(await pub.end()).toBe(0);

    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), 6 * 3600, 40_000)).toBe(
      6 * 3600,
    );
    const after = await mw.metrics();
    expect(after['points_written_total']).toBe(6 * 3600);
    expect(after['points_dropped_total']).toBe(0);
    expect(after['write_retries_total']).toBeGreaterThan(0);
    expect(after['spool_files']).toBe(0);
  },
);
