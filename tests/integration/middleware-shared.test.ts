/**
 * Issue 4, "it scales out": two middleware instances (own client ids, own spools) on one
 * shared subscription `$share/armtwin/arm/+/status`: the broker splits the stream, InfluxDB
 * gets exactly N points, and no point is written twice.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, expect, test } from 'vitest';
import { freePort } from '../helpers/ports.ts';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import {
  countPoints,
  publishAll,
  middlewareEnv,
  spawnMiddleware,
  statePayloads,
  tempDir,
  waitForValue,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux();
let dir = '';
const instances: MiddlewareProcess[] = [];

afterAll(async () => {
  await Promise.all(instances.map((m) => m.stop()));
  if (dir) fs.rmSync(dir, { recursive: true, force: true });
});

test(
  'two instances on a shared subscription: exactly N points, no duplicates',
  { timeout: 60_000 },
  async () => {
    dir = tempDir('mw-shared');
    for (const name of ['a', 'b']) {
      instances.push(
        await spawnMiddleware(
          middlewareEnv(
            { mqttUrl: broker().url, influx: influx() },
            `mw-shared-${name}`,
            dir,
            { MQTT_SHARE_GROUP: 'armtwin', FLUSH_INTERVAL_MS: '200' },
            `spool-${name}`,
          ),
          await freePort(),
          path.join(dir, `middleware-${name}.log`),
        ),
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
    const written = await Promise.all(
      instances.map(async (m) => (await m.metrics())['points_written_total'] ?? 0),
    );
    expect(written[0]! + written[1]!).toBe(6 * n); // every point written exactly once
    expect(written[0]).toBeGreaterThan(0);
    expect(written[1]).toBeGreaterThan(0);
    const messages = await Promise.all(
      instances.map(async (m) => (await m.metrics())['messages_total{topic="status"}'] ?? 0),
    );
    expect(messages[0]! + messages[1]!).toBe(n);
  },
);
