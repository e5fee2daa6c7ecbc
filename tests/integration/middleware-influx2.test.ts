/**
 * The middleware's write path on a real InfluxDB 2.7 (token auth, an org): it creates its bucket
 * when missing, N frames published on Mosquitto become exactly N points with their tags, fields
 * and times, the history API reads them back, and a wrong token is an auth failure that loses
 * nothing: the points wait in the spool and land once a good token is given.
 */
import { describe, expect, test } from 'vitest';
import { angleFromPwm } from '@armtwin/protocol';
import { useInflux2, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import {
  countPoints,
  publishAll,
  select,
  statePayloads,
  waitForValue,
} from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux2();
const T0 = Date.UTC(2026, 0, 1);
const BUCKET = 'armtwin-fresh'; // not made by the set-up: the middleware creates it
const OTHER_BUCKET = 'armtwin-other';

async function buckets(): Promise<string[]> {
  const { url, token } = influx();
  const res = await fetch(`${url}/api/v2/buckets`, {
    headers: { authorization: `Token ${token}` },
  });
  return ((await res.json()) as { buckets: { name: string }[] }).buckets.map((b) => b.name);
}

describe('middleware → InfluxDB 2.7', () => {
  const mws = useMiddlewares('mw-influx2', () => ({
    mqttUrl: broker().url,
    influx: { url: influx().url, token: influx().token, org: influx().org, bucket: BUCKET },
  }));

  test('creates its bucket, and N frames become exactly N points, read back by the history API', async () => {
    expect(await buckets()).not.toContain(BUCKET);
    const mw = await mws.spawn({ env: { FLUSH_INTERVAL_MS: '200' } });
    expect(await waitForValue(async () => (await buckets()).includes(BUCKET), true, 10_000)).toBe(
      true,
    );
    const messages = 200;
    await publishAll(broker().port, 'arm/arm1/status', statePayloads(messages, 6, T0), 1);
    await publishAll(broker().port, 'arm/arm1/status', [`$TIM:${T0 + 5}!{#000T045V7400!}`], 1);
    const inf = { url: influx().url, db: BUCKET, token: influx().token };
    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), messages * 6, 20_000)).toBe(
      messages * 6,
    );
    expect(await countPoints(inf, 'servo', 'temp')).toBe(1);
    const rows = await select(
      inf,
      `SELECT "pwm", "angle", "arm" FROM "servo" WHERE "id" = '002' ORDER BY time LIMIT 2`,
    );
    expect(rows).toEqual(
      [0, 1].map((k) => {
        const pwm = 500 + ((k * 7 + 200) % 2001);
        return [(T0 + k) * 1000, pwm, angleFromPwm(pwm), 'arm1'];
      }),
    );
    const res = await fetch(
      `http://127.0.0.1:${mw.port}/api/history/series?arm=arm1&id=002&field=pwm&start=${T0}&stop=${T0 + messages}`,
    );
    expect(res.status).toBe(200);
    const body = (await res.json()) as { series: { values: number[] }[] };
    expect(body.series[0]!.values.slice(0, 2)).toEqual(
      [0, 1].map((k) => 500 + ((k * 7 + 200) % 2001)),
    );
    expect((await mw.metrics())['points_dropped_total']).toBe(0);
    await mw.stop();
  });

  test('a wrong token is an auth failure that loses nothing, and the spooled batches go only to their own bucket', async () => {
    const inf = { url: influx().url, db: BUCKET, token: influx().token };
    const before = await countPoints(inf, 'servo', 'pwm');
    const bad = await mws.spawn({
      clientId: 'mw-influx2-bad',
      env: { FLUSH_INTERVAL_MS: '200', INFLUX_TOKEN: 'not-the-token' },
    });
    await publishAll(broker().port, 'arm/arm1/status', statePayloads(50, 6, T0 + 60_000), 1);
    const spooled = await waitForValue(
      async () => ((await bad.health()).body as { spool: { points: number } }).spool.points,
      300,
      20_000,
    );
    expect(spooled).toBe(300);
    expect(await countPoints(inf, 'servo', 'pwm')).toBe(before);
    await bad.stop();
    // The same spool, the right token, but another bucket: that run must not write the batches
    // meant for BUCKET into its own; it says they wait for another destination.
    const other = await mws.spawn({
      clientId: 'mw-influx2-bad',
      env: { FLUSH_INTERVAL_MS: '200', INFLUX_BUCKET: OTHER_BUCKET },
    });
    expect(
      await waitForValue(async () => (await buckets()).includes(OTHER_BUCKET), true, 10_000),
    ).toBe(true);
    expect((await other.metrics())['spool_other_destination_points']).toBe(300);
    expect(((await other.health()).body as { spool: { points: number } }).spool.points).toBe(0);
    await other.stop();
    expect(await countPoints({ ...inf, db: OTHER_BUCKET }, 'servo', 'pwm')).toBe(0);
    // The same client id and spool with the right token and bucket: the spooled points land.
    const good = await mws.spawn({ clientId: 'mw-influx2-bad', env: { FLUSH_INTERVAL_MS: '200' } });
    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), before + 300, 20_000)).toBe(
      before + 300,
    );
    expect((await good.metrics())['points_dropped_total']).toBe(0);
  });
});
