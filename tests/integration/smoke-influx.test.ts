/**
 * Smoke test for the real-services helper: a point written with @influxdata/influxdb-client to
 * a throwaway influxd (1.8, v2-compatible API) reads back with a Flux query, exactly; and
 * survives stop()/start() of the server.
 */
import { InfluxDB, Point } from '@influxdata/influxdb-client';
import { describe, expect, test } from 'vitest';
import { useInflux } from '../helpers/use-services.ts';

const influx = useInflux();
const TIME_MS = 1_700_000_000_123;

/** Rows of the test point, one per field, sorted by field name. */
async function readBack(url: string, bucket: string) {
  const flux = `from(bucket: "${bucket}")
  |> range(start: 2023-11-14T00:00:00Z, stop: 2023-11-15T00:00:00Z)
  |> filter(fn: (r) => r._measurement == "servo" and r.arm == "arm1" and r.id == "001")`;
  const rows = await new InfluxDB({ url, token: '' })
    .getQueryApi('')
    .collectRows<Record<string, unknown>>(flux);
  return rows
    .map((r) => ({ field: r._field, value: r._value, time: r._time, arm: r.arm, id: r.id }))
    .sort((a, b) => String(a.field).localeCompare(String(b.field)));
}

const EXPECTED = [
  { field: 'angle', value: 15.12, time: new Date(TIME_MS).toISOString(), arm: 'arm1', id: '001' },
  { field: 'pwm', value: 1612, time: new Date(TIME_MS).toISOString(), arm: 'arm1', id: '001' },
  { field: 'temp', value: 45.5, time: new Date(TIME_MS).toISOString(), arm: 'arm1', id: '001' },
  { field: 'volt', value: 7.4, time: new Date(TIME_MS).toISOString(), arm: 'arm1', id: '001' },
];

describe('InfluxDB smoke', () => {
  test('a point written with influxdb-client reads back with Flux', async () => {
    const { url, org, bucket, token } = influx();
    const writeApi = new InfluxDB({ url, token }).getWriteApi(org, bucket, 'ms');
    writeApi.writePoint(
      new Point('servo')
        .tag('arm', 'arm1')
        .tag('id', '001')
        .intField('pwm', 1612)
        .floatField('angle', 15.12)
        .floatField('temp', 45.5)
        .floatField('volt', 7.4)
        .timestamp(TIME_MS),
    );
    await writeApi.close();

    expect(await readBack(url, bucket)).toEqual(EXPECTED);
  });

  test('the data survives stop() and start() on the same port', async () => {
    const svc = influx();
    await svc.stop();
    await expect(fetch(`${svc.url}/ping`)).rejects.toThrow();
    await svc.start();
    expect(await readBack(svc.url, svc.bucket)).toEqual(EXPECTED);
  });
});
