/**
 * What an arm's state reports became in InfluxDB 1.8, for the tests that count them against the
 * sim's own counter (brokers-failover, cluster-nats): one `servo` point with `pwm` per report
 * (servo 000), and, when a count is off, where: the stored times that are not one report period
 * after the one before (a hole, or a report stored twice a few µs after its first copy); and the
 * counts per arm once all is stored.
 */
import { select, type InfluxTarget } from '../../apps/middleware/test/support/harness.ts';
import { until } from '../helpers/until.ts';

/**
 * The state reports of `arm` stored (0 while the database is not there yet); with `field` =
 * 'temp', its health reports.
 */
export async function storedReports(
  influx: InfluxTarget,
  arm: string,
  field: 'pwm' | 'temp' = 'pwm',
): Promise<number> {
  const rows = await select(
    influx,
    `SELECT count("${field}") FROM "servo" WHERE "arm" = '${arm}' AND "id" = '000'`,
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

/** A point of a servo stored twice: the same field with the same value, a few µs apart. */
export interface StoredTwice {
  id: string;
  /** The first copy's time (ISO) and how far after it the second is, µs. */
  at: string;
  us: number;
  field: string;
}

const SERVO_FIELDS = ['pwm', 'angle', 'temp', 'volt'] as const;

/**
 * Every servo point of `arm` that repeats the one before it on its servo within `withinUs`
 * (a field of both with one value): a report stored twice. An arm reporting at 50 Hz has no
 * two points of one servo that close otherwise (a health point shares its state report's point).
 */
export async function storedTwice(
  influx: InfluxTarget,
  arm: string,
  withinUs = 10,
): Promise<StoredTwice[]> {
  const rows = await select(
    influx,
    `SELECT "id", ${SERVO_FIELDS.map((f) => `"${f}"`).join(', ')} FROM "servo" WHERE "arm" = '${arm}'`,
  );
  const last = new Map<string, unknown[]>();
  const twice: StoredTwice[] = [];
  for (const row of rows) {
    const id = String(row[1]);
    const prev = last.get(id);
    last.set(id, row);
    const us = Number(row[0]) - Number(prev?.[0]);
    if (!prev || us > withinUs) continue;
    const field = SERVO_FIELDS.find((_, k) => row[k + 2] !== null && row[k + 2] === prev[k + 2]);
    if (field) twice.push({ id, at: new Date(Number(prev[0]) / 1000).toISOString(), us, field });
  }
  return twice;
}

/** What an arm's sim made and what of it is stored: state reports, and health reports. */
export interface StoredCount {
  published: number | undefined;
  stored: number;
  health: number | undefined;
  healthStored: number;
}

/**
 * Per arm, the reports its sim made (`published`, `healthSent`) and those stored, read once
 * every arm's are all stored, or once `ms` has passed (then the counts say what is missing).
 */
export async function storedCounts(
  influx: InfluxTarget,
  arms: readonly string[],
  published: ReadonlyMap<string, number>,
  healthSent: ReadonlyMap<string, number>,
  ms: number,
): Promise<Record<string, StoredCount>> {
  const settled = () =>
    Promise.all(
      arms.map(
        async (a) =>
          (await storedReports(influx, a)) === published.get(a) &&
          (await storedReports(influx, a, 'temp')) === healthSent.get(a),
      ),
    );
  await until(async () => (await settled()).every(Boolean), ms, 'every report stored', 200).catch(
    () => {},
  );
  return Object.fromEntries(
    await Promise.all(
      arms.map(async (a) => [
        a,
        {
          published: published.get(a),
          stored: await storedReports(influx, a),
          health: healthSent.get(a),
          healthStored: await storedReports(influx, a, 'temp'),
        },
      ]),
    ),
  ) as Record<string, StoredCount>;
}
