/**
 * What an arm's state reports became in InfluxDB 1.8, for the tests that count them against the
 * sim's own counter (brokers-failover, cluster-nats): one `servo` point with `pwm` per report
 * (servo 000), and, when a count is off, where: the stored times that are not one report period
 * after the one before (a hole, or a report stored twice a few µs after its first copy).
 */
import { select, type InfluxTarget } from '../../apps/middleware/test/support/harness.ts';

/** The state reports of `arm` stored (0 while the database is not there yet). */
export async function storedReports(influx: InfluxTarget, arm: string): Promise<number> {
  const rows = await select(
    influx,
    `SELECT count("pwm") FROM "servo" WHERE "arm" = '${arm}' AND "id" = '000'`,
  ).catch(() => []);
  return Number(rows[0]?.[1] ?? 0);
}

/** The steps between stored reports that are not `periodMs` (± 5 ms), with the time before each. */
export async function reportGaps(
  influx: InfluxTarget,
  arm: string,
  periodMs = 20,
): Promise<{ after: string; ms: number }[]> {
  const times = (
    await select(influx, `SELECT "pwm" FROM "servo" WHERE "arm" = '${arm}' AND "id" = '000'`)
  ).map((r) => Number(r[0]));
  return times
    .slice(1)
    .map((t, i) => ({
      after: new Date(times[i]! / 1000).toISOString(),
      ms: (t - times[i]!) / 1000,
    }))
    .filter((g) => Math.abs(g.ms - periodMs) > 5);
}
