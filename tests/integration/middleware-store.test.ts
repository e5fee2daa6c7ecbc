/**
 * Storage on the real Mosquitto and influxd: N frames published with mosquitto_pub become
 * exactly N points with the right tags, fields and times; malformed input is counted in
 * /metrics, never written, and does not crash the middleware. The writes are gzipped here
 * (`WRITE_GZIP=true`, level 1: what a remote InfluxDB gets by default; loopback goes plain).
 */
import { beforeAll, describe, expect, test } from 'vitest';
import { angleFromPwm } from '@armtwin/protocol';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import {
  countPoints,
  publishAll,
  select,
  statePayloads,
  waitForValue,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';

const broker = useMosquitto();
const influx = useInflux();
const T0 = Date.UTC(2026, 0, 1); // ms; $TIM of the first payload
const mws = useMiddlewares('mw-store', () => ({ mqttUrl: broker().url, influx: influx() }));
let mw: MiddlewareProcess;

beforeAll(async () => {
  mw = await mws.spawn({
    env: { FLUSH_INTERVAL_MS: '200', BATCH_SIZE: '500', WRITE_GZIP: 'true', WRITE_GZIP_LEVEL: '1' },
  });
});

describe('middleware → InfluxDB', () => {
  test('N frames become exactly N points with the right tags, fields and times', async () => {
    const messages = 400; // × 6 servos = 2400 position frames
    const payloads = statePayloads(messages, 6, T0);
    // health groups, stamped between state payloads
    for (let k = 0; k < 20; k++)
      payloads.push(`$TIM:${T0 + 10 * k}!{#000T045V7400!#001T061V6400!}`);
    await publishAll(broker().port, 'arm/arm1/status', payloads, 1);
    await publishAll(
      broker().port,
      'arm/arm1/control',
      [`$TIM:${T0}!{#000P1500T1000!#001P0900T1000!}`, `$TIM:${T0 + 1}!$KMS:100,0,200,-90,500!`],
      1,
    );
    await publishAll(broker().port, 'arm/arm1/status', [`$TIM:${T0 + 50}!$KMS:0!`], 1);

    const inf = { url: influx().url, db: influx().db };
    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), messages * 6, 20_000)).toBe(
      messages * 6,
    );
    expect(await countPoints(inf, 'servo', 'temp')).toBe(40);
    expect(await waitForValue(() => countPoints(inf, 'ik', 'code'), 1, 10_000)).toBe(1);
    expect(await countPoints(inf, 'command', 'pwm')).toBe(2);
    expect(await countPoints(inf, 'servo', 'angle')).toBe(messages * 6);

    // tags, fields, times: servo 002 of payload k has pwm 500 + (7k + 200) % 2001, time T0 + k ms
    const rows = await select(
      inf,
      `SELECT "pwm", "angle", "arm" FROM "servo" WHERE "id" = '002' AND "pwm" > 0 ORDER BY time LIMIT 3`,
    );
    expect(rows).toEqual(
      [0, 1, 2].map((k) => {
        const pwm = 500 + ((k * 7 + 200) % 2001);
        return [(T0 + k) * 1000, pwm, angleFromPwm(pwm), 'arm1'];
      }),
    );
    const health = await select(
      inf,
      `SELECT "temp", "volt" FROM "servo" WHERE "id" = '001' AND "temp" > 0 ORDER BY time LIMIT 1`,
    );
    expect(health[0]?.slice(1)).toEqual([61, 6.4]);
    const cmd = await select(inf, `SELECT "pwm", "angle", "ms" FROM "command" WHERE "id" = '001'`);
    expect(cmd).toEqual([[T0 * 1000, 900, angleFromPwm(900), 1000]]);
    const ik = await select(
      inf,
      `SELECT "code", "x", "y", "z", "a" FROM "ik" WHERE "arm" = 'arm1'`,
    );
    expect(ik).toEqual([[(T0 + 50) * 1000, 0, 100, 0, 200, -90]]);

    // the same data through the middleware's history API (1 ms windows over 400 ms)
    const res = await fetch(
      `http://127.0.0.1:${mw.port}/api/history/series?arm=arm1&id=002&field=pwm&start=${T0}&stop=${T0 + messages}`,
    );
    expect(res.status).toBe(200);
    const body = (await res.json()) as { series: { id: string; values: number[] }[] };
    expect(body.series).toHaveLength(1);
    expect(body.series[0]!.values.slice(0, 3)).toEqual(
      [0, 1, 2].map((k) => 500 + ((k * 7 + 200) % 2001)),
    );
    const bad = await fetch(`http://127.0.0.1:${mw.port}/api/history/series?arm=ARM%221&field=pwm`);
    expect(bad.status).toBe(400);
    expect(await bad.json()).toMatchObject({ parameter: 'arm' });

    const m = await mw.metrics();
    expect(m['points_written_total']).toBe(messages * 6 + 40 + 2 + 1);
    expect(m['points_dropped_total']).toBe(0);
    expect(m['frames_total{kind="position"}']).toBe(messages * 6);
  });

  test('malformed frames are counted in /metrics, never written, and do not crash it', async () => {
    const inf = { url: influx().url, db: influx().db };
    const before = await countPoints(inf, 'servo', 'pwm');
    const bad = [
      'hello world',
      '#000P9999!', // pwm out of range
      '#00XP1500!', // malformed
      '{#000P1500!#001P', // group cut short by the next message: its one valid frame is kept
      '}}}!!!',
      '#' + '1'.repeat(200),
      `$TIM:${T0 + 5000}!#007P1500!`, // a good frame among them
      '\u0000\u00ff binary',
    ];
    await publishAll(broker().port, 'arm/arm1/status', bad, 1);
    expect(await waitForValue(() => countPoints(inf, 'servo', 'pwm'), before + 2, 10_000)).toBe(
      before + 2,
    );
    const m = await mw.metrics();
    const rejected = Object.entries(m).filter(([k]) => k.startsWith('frames_rejected_total'));
    expect(rejected.length).toBeGreaterThanOrEqual(4);
    expect(m['frames_rejected_total{reason="out-of-range"}']).toBeGreaterThanOrEqual(1);
    expect(m['frames_rejected_total{reason="malformed"}']).toBeGreaterThanOrEqual(1);
    expect(m['points_dropped_total']).toBe(0);
    const h = await mw.health();
    expect(h.status).toBe(200);
    expect(h.body).toMatchObject({
      storage: true,
      mqtt: { connected: true },
      influx: { reachable: true },
    });
    expect(mw.child.exitCode).toBeNull();
  });
});
