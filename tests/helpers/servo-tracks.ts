/**
 * What InfluxDB 1.8 holds of an arm's servos, read back with InfluxQL for a test: each servo's
 * angles in time order (its reports in `servo`, or the commanded targets in `command`), and the
 * value in force at a time.
 */
import { select, type InfluxTarget } from '../../apps/middleware/test/support/harness.ts';

/** InfluxQL rows [µs, angle] per servo id of `measurement` for `arm` in [fromUs, toUs), in time order. */
export async function servoTracks(
  influx: InfluxTarget,
  measurement: string,
  arm: string,
  fromUs: number,
  toUs: number,
): Promise<Map<number, [number, number][]>> {
  const rows = await select(
    influx,
    `SELECT "angle", "id" FROM "${measurement}" WHERE "arm" = '${arm}' AND time >= ${fromUs}u AND time < ${toUs}u AND "angle" > -1000`,
  );
  const out = new Map<number, [number, number][]>();
  for (const [t, angle, id] of rows as [number, number, string][]) {
    const list = out.get(Number(id)) ?? [];
    list.push([t, angle]);
    out.set(Number(id), list);
  }
  return out;
}

/** The value in force at µs `t`: the last of `track` at or before it. */
export const heldAt = (track: [number, number][] | undefined, t: number) =>
  track?.filter(([at]) => at <= t).at(-1)?.[1];
