/**
 * Middlewares sharing one JetStream consumer (NATS_URL, docs/cluster.md): how many status
 * messages each took (its `/metrics`), and the wait until the consumer takes messages at all
 * (a report sent on a stand-in arm, again each poll, until one middleware counts it).
 */
import type { MqttClient } from 'mqtt';
import type { MiddlewareProcess } from '../../apps/middleware/test/support/harness.ts';
import { until } from './until.ts';

/** The status messages each middleware took, in order (0 while its metrics do not answer). */
export async function statusTaken(mws: readonly MiddlewareProcess[]): Promise<number[]> {
  const m = await Promise.all(mws.map((x) => x.metrics().catch(() => ({}))));
  return m.map((x: Record<string, number>) => x['messages_total{topic="status"}'] ?? 0);
}

/** Publishes a status report on `arm/probe/status` until a middleware took one; how many were sent. */
export async function probeUntilTaken(
  probe: MqttClient,
  mws: readonly MiddlewareProcess[],
  ms: number,
): Promise<number> {
  let probes = 0;
  await until(
    async () => {
      await probe.publishAsync('arm/probe/status', `$TIM:${Date.now()}!#000P1500!`, { qos: 1 });
      probes++;
      return (await statusTaken(mws)).some((n) => n > 0);
    },
    ms,
    'the shared consumer taking messages',
    200,
  );
  return probes;
}
