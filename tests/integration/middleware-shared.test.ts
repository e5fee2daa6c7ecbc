/**
 * "It scales out": two middleware instances (own client ids, own spools) on one
 * shared subscription `$share/armtwin/arm/+/status`: the broker splits the stream, InfluxDB
 * gets exactly N points, and no point is written twice.
 */
import { expect, test } from 'vitest';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import {
  countPoints,
  publishAll,
  statePayloads,
  waitForValue,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-shared', () => ({ mqttUrl: broker().url, influx: influx() }));
const instances: MiddlewareProcess[] = [];

test(
  'two instances on a shared subscription: exactly N points, no duplicates',
  { timeout: 60_000 },
  async () => {
    for (const name of ['a', 'b']) {
      instances.push(
        await mws.spawn({
          clientId: `mw-shared-${name}`,
          env: { MQTT_SHARE_GROUP: 'armtwin', FLUSH_INTERVAL_MS: '200' },
        }),
      );
    }
    const n = 2000;
    await publishAll(
      broker().port,
      'arm/arm1/status',
      statePayloads(n, 6, Date.UTC(2026, 3, 1)),
      1,
    );
    const inf = { url: influx().url, db: influx().db };
    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), 6 * n, 20_000)).toBe(6 * n);
    const writtenNow = () =>
      Promise.all(instances.map(async (m) => (await m.metrics())['points_written_total'] ?? 0));
    // influxd shows a batch before the middleware has read its 204 and counted it
    const sum = async () => (await writtenNow()).reduce((a, b) => a + b, 0);
    expect(await waitForValue(sum, 6 * n, 10_000)).toBe(6 * n); // every point written exactly once
    const written = await writtenNow();
    expect(written[0]).toBeGreaterThan(0);
    expect(written[1]).toBeGreaterThan(0);
    const messages = await Promise.all(
      instances.map(async (m) => (await m.metrics())['messages_total{topic="status"}'] ?? 0),
    );
    expect(messages[0]! + messages[1]!).toBe(n);
  },
);
