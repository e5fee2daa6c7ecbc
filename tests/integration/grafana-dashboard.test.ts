/**
 * Every query of both dashboards (panels and variables), with Grafana's macros replaced by real
 * values, run on known data against real InfluxDB servers, 1.8 and 2.7 (the same answers from
 * both): the Flux one (deploy/grafana/dashboards/armtwin.json) and the InfluxQL one
 * (armtwin-influxql.json, through the v1 `/query` API that InfluxDB 3 serves too).
 */
import fs from 'node:fs';
import path from 'node:path';
import { InfluxDB } from '@influxdata/influxdb-client';
import { beforeAll, describe, expect, test } from 'vitest';
import { queryV1 } from '@armtwin/middleware/history';
import { REPO_ROOT } from '../helpers/files.ts';
import { INFLUX_SERVERS } from '../helpers/use-services.ts';

const DASHBOARD = path.join(REPO_ROOT, 'deploy', 'grafana', 'dashboards', 'armtwin.json');
const INFLUXQL_DASHBOARD = path.join(path.dirname(DASHBOARD), 'armtwin-influxql.json');
const T0 = Date.UTC(2024, 0, 1);
const WINDOW_S = 10;

interface FluxQuery {
  /** Where it sits: `panel <title> / <refId>` or `variable <name>`. */
  where: string;
  query: string;
}

/** Every `query` string in the dashboard: panel targets and query variables. */
function dashboardQueries(file = DASHBOARD): FluxQuery[] {
  const dash = JSON.parse(fs.readFileSync(file, 'utf8'));
  const out: FluxQuery[] = [];
  for (const p of dash.panels ?? []) {
    for (const t of p.targets ?? [])
      out.push({ where: `panel ${p.title} / ${t.refId}`, query: t.query });
  }
  for (const v of dash.templating?.list ?? []) {
    if (v.type === 'query') out.push({ where: `variable ${v.name}`, query: v.query });
  }
  return out;
}

/** Grafana's macros and our variables → a runnable Flux script. */
function substitute(query: string, bucket: string): string {
  const q = query
    .replaceAll('v.timeRangeStart', new Date(T0).toISOString())
    .replaceAll('v.timeRangeStop', new Date(T0 + 60_000).toISOString())
    .replaceAll('v.windowPeriod', `${WINDOW_S}s`)
    .replaceAll('v.defaultBucket', JSON.stringify(bucket))
    .replaceAll('${arm}', 'arm1');
  expect(q, 'every macro and variable replaced').not.toMatch(/\bv\.[a-zA-Z]|\$/);
  return q;
}

/** Grafana's InfluxQL macros (`$timeFilter` includes its stop) and our variable → a statement. */
function substituteInfluxql(query: string): string {
  const q = query
    .replaceAll('$timeFilter', `time >= ${T0}ms and time <= ${T0 + 60_000}ms`)
    .replaceAll('$__interval', `${WINDOW_S}s`)
    .replaceAll('$arm', 'arm1');
  expect(q, 'every macro and variable replaced').not.toMatch(/\$/);
  return q;
}

// Known data, one sample per second over [T0, T0 + 60 s) (nothing on the stop instant).
const temp = (id: number, s: number) => (id === 0 ? 40 + s * 0.5 : 50 + (s % 3));
const volt = (id: number, s: number) => (id === 0 ? (s === 25 ? 6.2 : 7.4) : s === 47 ? 6.0 : 7.3);
const COMMANDS: [number, number][] = [
  [5, 10],
  [30, 20],
  [33, 25],
];

describe.each(INFLUX_SERVERS)('InfluxDB $version', ({ use }) => {
  const influx = use();

  beforeAll(async () => {
    const { url, token, org, bucket } = influx();
    const w = new InfluxDB({ url, token }).getWriteApi(org, bucket, 'ms');
    for (let s = 0; s < 60; s++) {
      const t = T0 + s * 1000;
      for (const id of [0, 1]) {
        w.writeRecord(
          `servo,arm=arm1,id=00${id} temp=${temp(id, s)},volt=${volt(id, s)},angle=${s + id} ${t}`,
        );
      }
      w.writeRecord(`servo,arm=arm2,id=000 temp=99,volt=5,angle=-90 ${t}`);
    }
    for (const [s, angle] of COMMANDS)
      w.writeRecord(`command,arm=arm1,id=000 pwm=1500i,angle=${angle},ms=100i ${T0 + s * 1000}`);
    await w.close();
  });

  /** Runs one dashboard query; rows keep only the columns a panel would plot. */
  async function run(q: FluxQuery) {
    const { url, token, org, bucket } = influx();
    return new InfluxDB({ url, token })
      .getQueryApi(org)
      .collectRows<Record<string, unknown>>(substitute(q.query, bucket));
  }

  const find = (re: RegExp) => {
    const q = dashboardQueries().find((x) => re.test(x.where));
    if (!q) throw new Error(`no query matching ${re}`);
    return q;
  };

  /** Window end times (Grafana's default `_stop`) for the six 10 s windows. */
  const windowEnds = Array.from({ length: 6 }, (_, k) => T0 + (k + 1) * WINDOW_S * 1000);
  const ms = (t: unknown) => Date.parse(String(t));
  const windowed = (f: (s: number) => number, agg: (xs: number[]) => number) =>
    Array.from({ length: 6 }, (_, k) =>
      agg(Array.from({ length: WINDOW_S }, (_, j) => f(k * WINDOW_S + j))),
    );
  const mean = (xs: number[]) => xs.reduce((a, b) => a + b, 0) / xs.length;

  describe('deploy/grafana/dashboards/armtwin.json', () => {
    test('refreshes every 5 s, has the $arm variable and the three panels', () => {
      const dash = JSON.parse(fs.readFileSync(DASHBOARD, 'utf8'));
      expect(dash.refresh).toBe('5s');
      expect(dash.templating.list.map((v: { name: string }) => v.name)).toEqual(['arm']);
      expect(dash.panels).toHaveLength(3);
      expect(dashboardQueries().map((q) => q.where)).toHaveLength(5);
      const volt = dash.panels.find((p: { title: string }) => /voltage/i.test(p.title));
      expect(volt.fieldConfig.defaults.thresholds.steps).toEqual([
        { color: 'red', value: null },
        { color: 'green', value: 6.5 },
      ]);
    });

    test.each(dashboardQueries().map((q) => [q.where, q] as const))(
      '%s runs on the real influxd and returns rows',
      async (_where, q) => {
        expect((await run(q)).length).toBeGreaterThan(0);
      },
    );

    test('the $arm variable lists every arm once', async () => {
      const rows = await run(find(/^variable arm/));
      expect(rows.map((r) => r._value).sort()).toEqual(['arm1', 'arm2']);
    });

    test('temperature: exact mean per window, one series per servo id, only $arm', async () => {
      const rows = await run(find(/temperature/));
      for (const id of [0, 1]) {
        const mine = rows.filter((r) => r.id === `00${id}`);
        expect(mine.map((r) => ms(r._time))).toEqual(windowEnds);
        expect(mine.map((r) => r._value)).toEqual(windowed((s) => temp(id, s), mean));
      }
      expect(rows).toHaveLength(12);
    });

    test('bus voltage: one series, the lowest servo reading per window', async () => {
      const rows = await run(find(/voltage/));
      expect(rows.map((r) => ms(r._time))).toEqual(windowEnds);
      expect(rows.map((r) => r._value)).toEqual([7.3, 7.3, 6.2, 7.3, 6.0, 7.3]);
      expect(new Set(rows.map((r) => r.arm))).toEqual(new Set(['arm1']));
    });

    test('angles: actual mean per window per id, and the last commanded target per window', async () => {
      const actual = await run(find(/Joint angles.* \/ A$/));
      expect(actual.filter((r) => r.id === '001').map((r) => r._value)).toEqual(
        windowed((s) => s + 1, mean),
      );
      const commanded = await run(find(/Joint angles.* \/ B$/));
      expect(commanded.map((r) => [ms(r._time), r._value, r.id])).toEqual([
        [windowEnds[0], 10, '000'],
        [windowEnds[3], 25, '000'],
      ]);
    });
  });
  describe('deploy/grafana/dashboards/armtwin-influxql.json', () => {
    const queries = () => dashboardQueries(INFLUXQL_DASHBOARD);
    const runQl = async (q: FluxQuery) => {
      const { url, token, org, bucket } = influx();
      const [rows] = await queryV1({ url, token, org, bucket, timeoutMs: 30_000 }, [
        substituteInfluxql(q.query),
      ]);
      return rows!;
    };
    const findQl = (re: RegExp) => {
      const q = queries().find((x) => re.test(x.where));
      if (!q) throw new Error(`no query matching ${re}`);
      return q;
    };
    /** InfluxQL stamps a window at its start. */
    const windowStarts = windowEnds.map((t) => t - WINDOW_S * 1000);

    test('the same panels, thresholds and variable as the Flux dashboard, on its own datasource', () => {
      const flux = JSON.parse(fs.readFileSync(DASHBOARD, 'utf8'));
      const ql = JSON.parse(fs.readFileSync(INFLUXQL_DASHBOARD, 'utf8'));
      expect(ql.uid).not.toBe(flux.uid);
      expect(ql.panels.map((p: { title: string }) => p.title)).toEqual(
        flux.panels.map((p: { title: string }) => p.title),
      );
      expect(ql.panels.map((p: { fieldConfig: unknown }) => p.fieldConfig)).toEqual(
        flux.panels.map((p: { fieldConfig: unknown }) => p.fieldConfig),
      );
      expect(ql.templating.list.map((v: { name: string }) => v.name)).toEqual(['arm']);
      expect(queries()).toHaveLength(5);
      for (const p of ql.panels) expect(p.datasource.uid).toBe('armtwin-influxql');
    });

    test.each(queries().map((q) => [q.where, q] as const))(
      '%s runs on the real influxd and returns rows',
      async (_where, q) => {
        expect((await runQl(q)).length).toBeGreaterThan(0);
      },
    );

    test('the $arm variable lists every arm once', async () => {
      const rows = await runQl(findQl(/^variable arm/));
      expect(rows.map((r) => r.value).sort()).toEqual(['arm1', 'arm2']);
    });

    test('temperature: exact mean per window, one series per servo id, only $arm', async () => {
      const rows = await runQl(findQl(/temperature/));
      for (const id of [0, 1]) {
        const mine = rows.filter((r) => r.id === `00${id}`);
        expect(mine.map((r) => ms(r._time))).toEqual(windowStarts);
        expect(mine.map((r) => r._value)).toEqual(windowed((s) => temp(id, s), mean));
      }
      expect(rows).toHaveLength(12);
    });

    test('bus voltage: one series, the lowest servo reading per window', async () => {
      const rows = await runQl(findQl(/voltage/));
      expect(rows.map((r) => ms(r._time))).toEqual(windowStarts);
      expect(rows.map((r) => r._value)).toEqual([7.3, 7.3, 6.2, 7.3, 6.0, 7.3]);
    });

    test('angles: actual mean per window per id, and the last commanded target per window', async () => {
      const actual = await runQl(findQl(/Joint angles.* \/ A$/));
      expect(actual.filter((r) => r.id === '001').map((r) => r._value)).toEqual(
        windowed((s) => s + 1, mean),
      );
      const commanded = await runQl(findQl(/Joint angles.* \/ B$/));
      expect(commanded.map((r) => [ms(r._time), r._value, r.id])).toEqual([
        [windowStarts[0], 10, '000'],
        [windowStarts[3], 25, '000'],
      ]);
    });
  });
});
