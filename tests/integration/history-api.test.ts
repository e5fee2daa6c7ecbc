/**
 * The history API against real InfluxDB servers, 1.8 and 2.7 (token auth, an org and a bucket),
 * in both query languages (InfluxQL over the v1 `/query` API, Flux), over a real node:http
 * server: the same known points in, the same exact figures out of all four.
 */
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import { InfluxDB, type QueryApi } from '@influxdata/influxdb-client';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import {
  createHistoryHandler,
  historyReader,
  influxqlReader,
  QUERY_LANGUAGES,
  type HistoryHandlerDeps,
} from '../../apps/middleware/src/history/index.ts';
import { seriesQuery } from '../../apps/middleware/src/history/queries.ts';
import { INFLUX_SERVERS } from '../helpers/use-services.ts';

const T0 = Date.UTC(2024, 0, 1); // series: 100 min of temp at 1 Hz
const T1 = T0 + 2 * 3_600_000; // alarms
const T2 = T0 + 3 * 3_600_000; // tracking and pose
const NOW = T0 + 4 * 3_600_000;
const SERIES_S = 6000;

/** Temperature of servo `id` at second `s` of the series block (multiples of 0.25: exact sums). */
const tempAt = (id: number, s: number) => 40 + ((s * 7) % 11) * 0.25 + id;

function lines(): string[] {
  const out: string[] = [];
  for (let s = 0; s < SERIES_S; s++) {
    const t = T0 + s * 1000;
    out.push(`servo,arm=arm1,id=000 temp=${tempAt(0, s)},pwm=${1500 + (s % 4)}i ${t}`);
    out.push(`servo,arm=arm1,id=001 temp=${tempAt(1, s)} ${t}`);
    out.push(`servo,arm=arm2,id=000 temp=99 ${t}`); // another arm: never in arm1's answers
  }
  // Alarms: temp of 002 and volt of 003, one sample per second from T1 (after 15 normal minutes).
  for (let s = 0; s < 900; s++)
    out.push(`servo,arm=arm1,id=002 temp=45,volt=7.4 ${T1 - 900_000 + s * 1000}`);
  [50, 60, 65, 75, 80, 74, 59.9, 55, 76, 70].forEach((v, i) =>
    out.push(`servo,arm=arm1,id=002 temp=${v} ${T1 + i * 1000}`),
  );
  [7.4, 6.5, 6.49, 6.0, 6.2, 6.5, 7.0].forEach((v, i) =>
    out.push(`servo,arm=arm1,id=003 volt=${v} ${T1 + i * 1000}`),
  );
  out.push(`servo,arm=arm2,id=002 temp=90 ${T1 + 500}`);
  // Control events (measurement audit, as the middleware stores arm/{id}/audit).
  out.push(`audit,arm=arm1,kind=taken by="alice",detail="alice took control" ${T1 + 40_000}`);
  out.push(
    `audit,arm=arm1,kind=refused-command by="bob",detail="controlled by alice, \\"ask\\"" ${T1 + 41_000}`,
  );
  out.push(`audit,arm=arm2,kind=taken by="carol",detail="carol took control" ${T1 + 40_500}`);
  // Commands of 007 by two authors (the `user` tag of a per-user control topic): two series, one servo.
  out.push(`command,arm=arm1,id=007,user=alice pwm=1500i,angle=5,ms=100i ${T1 + 30_000}`);
  out.push(`command,arm=arm1,id=007,user=bob pwm=1500i,angle=7,ms=100i ${T1 + 31_000}`);
  // Tracking, 004: step to 0, then at +1000 a 500 ms move to 20° that lags and overshoots.
  out.push(`command,arm=arm1,id=004 pwm=1500i,angle=0,ms=0i ${T2}`);
  out.push(`command,arm=arm1,id=004 pwm=1648i,angle=20,ms=500i ${T2 + 1000}`);
  const a004: Record<number, number> = {
    1100: 3,
    1200: 6,
    1300: 10,
    1400: 14,
    1500: 18,
    1600: 20,
    1700: 21,
  };
  // 005: a command long before the range (found by the lookback); the arm sits 0.5° off.
  out.push(`command,arm=arm1,id=005 pwm=1870i,angle=50,ms=0i ${T2 - 5000}`);
  // 006: a command 200 ms before the range, still ramping at its start, from 0 (sample at -300).
  out.push(`command,arm=arm1,id=006 pwm=1574i,angle=10,ms=400i ${T2 - 200}`);
  out.push(`servo,arm=arm1,id=006 angle=0 ${T2 - 300}`);
  const a006: Record<number, number> = { 0: 5, 100: 8 };
  for (let ms = 0; ms < 3000; ms += 100) {
    out.push(`servo,arm=arm1,id=004 angle=${a004[ms] ?? (ms < 1100 ? 0 : 20)} ${T2 + ms}`);
    out.push(`servo,arm=arm1,id=005 angle=49.5 ${T2 + ms}`);
    out.push(`servo,arm=arm1,id=006 angle=${a006[ms] ?? 10} ${T2 + ms}`);
  }
  return out;
}

describe.each(INFLUX_SERVERS)('InfluxDB $version', ({ use }) => {
  const influx = use();
  let queryApi: QueryApi;

  beforeAll(async () => {
    const { url, org, bucket, token } = influx();
    const writeApi = new InfluxDB({ url, token }).getWriteApi(org, bucket, 'ms', {
      batchSize: 5000,
    });
    writeApi.writeRecords(lines());
    await writeApi.close();
    queryApi = new InfluxDB({ url, token }).getQueryApi(org);
  });

  describe.each(QUERY_LANGUAGES)('%s', (language) => {
    let base = '';

    function serve(
      deps: Partial<HistoryHandlerDeps> = {},
    ): Promise<{ url: string; close: () => Promise<void> }> {
      const { url, bucket, token, org } = influx();
      const handler = createHistoryHandler({
        reader: historyReader({ url, token, org, bucket, timeoutMs: 30_000 }, language),
        now: () => NOW,
        ...deps,
      });
      const srv = http.createServer((req, res) => {
        handler(req, res)
          .then((mine) => mine || res.writeHead(404).end())
          .catch(() => res.writeHead(500).end());
      });
      return new Promise((resolve) =>
        srv.listen(0, '127.0.0.1', () =>
          resolve({
            url: `http://127.0.0.1:${(srv.address() as AddressInfo).port}`,
            close: () => new Promise<void>((r) => srv.close(() => r())),
          }),
        ),
      );
    }

    let closeMain: () => Promise<void>;
    beforeAll(async () => {
      const s = await serve();
      base = s.url;
      closeMain = s.close;
    });
    afterAll(async () => {
      await closeMain?.();
    });

    const get = async (path: string) => {
      const res = await fetch(base + path);
      // The answers are checked field by field below; a loose type keeps that readable.
      // eslint-disable-next-line @typescript-eslint/no-explicit-any
      return { status: res.status, body: (await res.json()) as Record<string, any> };
    };

    describe('GET /history/series', () => {
      test('exact means per 5 s window over 100 minutes, per servo id, only the asked arm', async () => {
        const r = await get(
          `/history/series?arm=arm1&field=temp&id=all&start=${T0}&stop=${T0 + SERIES_S * 1000}`,
        );
        expect(r.status).toBe(200);
        expect(r.body.every).toBe('5s');
        expect(r.body.series.map((s: { id: string }) => s.id)).toEqual(['000', '001']);
        for (const [i, s] of r.body.series.entries()) {
          expect(s.times).toHaveLength(1200);
          expect(s.values).toHaveLength(1200);
          for (let k = 0; k < 1200; k++) {
            let sum = 0;
            for (let j = 0; j < 5; j++) sum += tempAt(i, 5 * k + j);
            expect(s.times[k]).toBe(T0 + 5000 * k); // the window's start
            expect(s.values[k]).toBe(sum / 5);
          }
        }
      });

      test('one id, an integer field, RFC 3339 times', async () => {
        const start = new Date(T0).toISOString();
        const stop = new Date(T0 + 20_000).toISOString();
        const r = await get(
          `/history/series?arm=arm1&field=pwm&id=000&start=${start}&stop=${stop}`,
        );
        expect(r.body.every).toBe('10ms');
        expect(r.body.series).toEqual([
          {
            id: '000',
            times: Array.from({ length: 20 }, (_, s) => T0 + s * 1000),
            values: Array.from({ length: 20 }, (_, s) => 1500 + (s % 4)),
          },
        ]);
      });

      test("commands by two authors are one servo's series", async () => {
        const r = await get(
          `/history/series?arm=arm1&field=command&id=007&start=${T1 + 29_000}&stop=${T1 + 33_000}`,
        );
        expect(r.body.series).toEqual([
          { id: '007', times: [T1 + 30_000, T1 + 31_000], values: [5, 7] },
        ]);
      });

      test('no data in range: an empty list', async () => {
        const r = await get(`/history/series?arm=arm1&field=volt&id=000&start=-5m`);
        expect(r).toEqual({ status: 200, body: expect.objectContaining({ series: [] }) });
      });
    });

    describe('GET /history/alarms', () => {
      test('episodes with exact start, end and peak; nested critical; an open one', async () => {
        const r = await get(`/history/alarms?arm=arm1&start=${T1 - 3_600_000}&stop=${T1 + 60_000}`);
        expect(r.status).toBe(200);
        expect(r.body.truncated).toBe(false);
        expect(r.body.episodes).toEqual([
          {
            kind: 'temp-warning',
            arm: 'arm1',
            id: '002',
            start: T1 + 1000,
            end: T1 + 6000,
            peak: 80,
          },
          {
            kind: 'undervoltage',
            arm: 'arm1',
            id: '003',
            start: T1 + 2000,
            end: T1 + 5000,
            peak: 6,
          },
          {
            kind: 'temp-critical',
            arm: 'arm1',
            id: '002',
            start: T1 + 3000,
            end: T1 + 5000,
            peak: 80,
          },
          { kind: 'temp-warning', arm: 'arm1', id: '002', start: T1 + 8000, end: null, peak: 76 },
          {
            kind: 'temp-critical',
            arm: 'arm1',
            id: '002',
            start: T1 + 8000,
            end: T1 + 9000,
            peak: 76,
          },
        ]);
      });

      test('filtered by id; a range starting inside an episode starts it at its first sample', async () => {
        const r = await get(`/history/alarms?arm=arm1&id=002&start=${T1 + 4000}&stop=${T1 + 8500}`);
        expect(r.body.episodes).toEqual([
          {
            kind: 'temp-warning',
            arm: 'arm1',
            id: '002',
            start: T1 + 4000,
            end: T1 + 6000,
            peak: 80,
          },
          {
            kind: 'temp-critical',
            arm: 'arm1',
            id: '002',
            start: T1 + 4000,
            end: T1 + 5000,
            peak: 80,
          },
          { kind: 'temp-warning', arm: 'arm1', id: '002', start: T1 + 8000, end: null, peak: 76 },
          { kind: 'temp-critical', arm: 'arm1', id: '002', start: T1 + 8000, end: null, peak: 76 },
        ]);
      });

      test('the row bound is reported', async () => {
        const small = await serve({ options: { maxAlarmRows: 3 } });
        try {
          const res = await fetch(
            `${small.url}/history/alarms?arm=arm1&id=002&start=${T1}&stop=${T1 + 60_000}`,
          );
          const body = (await res.json()) as { truncated: boolean };
          expect(body.truncated).toBe(true);
        } finally {
          await small.close();
        }
      });
    });

    describe('GET /history/tracking', () => {
      test('exact mean and maximum absolute error per joint', async () => {
        const r = await get(`/history/tracking?arm=arm1&start=${T2}&stop=${T2 + 3000}`);
        expect(r.status).toBe(200);
        expect(r.body.thinnedEveryMs).toBeNull();
        const byId = Object.fromEntries(r.body.joints.map((j: { id: string }) => [j.id, j]));
        // 007 has commands (by two authors, found by the lookback) and no samples.
        expect(Object.keys(byId)).toEqual(['004', '005', '006', '007']);
        expect(byId['007']).toMatchObject({ samples: 0, meanAbsError: null });
        // 004: errors 1, 2, 2, 2, 2, 0, 1 at +1100…+1700, 0 elsewhere; 30 samples.
        expect(byId['004'].samples).toBe(30);
        expect(byId['004'].meanAbsError).toBeCloseTo(10 / 30, 12);
        expect(byId['004'].maxAbsError).toBeCloseTo(2, 12);
        expect(byId['004'].maxAt).toBe(T2 + 1200);
        expect(byId['005']).toEqual({
          id: '005',
          samples: 30,
          meanAbsError: 0.5,
          maxAbsError: 0.5,
          maxAt: T2,
        });
        expect(byId['006'].samples).toBe(30);
        expect(byId['006'].meanAbsError).toBeCloseTo(0.5 / 30, 12);
        expect(byId['006'].maxAbsError).toBeCloseTo(0.5, 12);
        expect(byId['006'].maxAt).toBe(T2 + 100);
      });

      test('dense data is thinned to the first sample per window, and said so', async () => {
        const small = await serve({ options: { maxTrackingSamples: 10 } });
        try {
          const res = await fetch(
            `${small.url}/history/tracking?arm=arm1&id=005&start=${T2}&stop=${T2 + 3000}`,
          );
          const body = (await res.json()) as {
            thinnedEveryMs: number | null;
            joints: { samples: number; meanAbsError: number }[];
          };
          // 005 has 30 samples in [T2 - 11 s, T2 + 3 s), more than 10: 2 s windows (8 of them);
          // those in range are the first of [T2, T2 + 2 s) and of [T2 + 2 s, T2 + 4 s).
          expect(body.thinnedEveryMs).toBe(2000);
          expect(body.joints[0]).toMatchObject({ samples: 2, meanAbsError: 0.5 });
        } finally {
          await small.close();
        }
      });
    });

    describe('GET /history/audit', () => {
      const range = `arm=arm1&start=${T1 + 39_000}&stop=${T1 + 50_000}`;
      test("the arm's control events in time order, only that arm's", async () => {
        const r = await get(`/history/audit?${range}`);
        expect(r.status).toBe(200);
        expect(r.body).toMatchObject({ truncated: false });
        expect(r.body.events).toEqual([
          { at: T1 + 40_000, by: 'alice', kind: 'taken', detail: 'alice took control' },
          {
            at: T1 + 41_000,
            by: 'bob',
            kind: 'refused-command',
            detail: 'controlled by alice, "ask"',
          },
        ]);
      });

      test('as CSV, quoted where a cell needs it', async () => {
        const res = await fetch(`${base}/history/audit?${range}&format=csv`);
        expect(res.headers.get('content-type')).toMatch(/^text\/csv/);
        expect(await res.text()).toBe(
          'time,by,kind,detail\n' +
            `${new Date(T1 + 40_000).toISOString()},alice,taken,alice took control\n` +
            `${new Date(T1 + 41_000).toISOString()},bob,refused-command,"controlled by alice, ""ask"""\n`,
        );
      });
    });

    describe('GET /history/pose', () => {
      test('the first angle of every servo per window, at the window start, as frames for replay', async () => {
        const r = await get(`/history/pose?arm=arm1&start=${T2}&stop=${T2 + 3000}`);
        expect(r.status).toBe(200);
        expect(r.body.every).toBe('2ms');
        expect(r.body.ids).toEqual(['004', '005', '006']);
        expect(r.body.times).toHaveLength(30);
        expect(r.body.times).toEqual(Array.from({ length: 30 }, (_, k) => T2 + 100 * k));
        expect(r.body.angles[0]).toEqual([0, 49.5, 5]);
        expect(r.body.angles[13]).toEqual([10, 49.5, 10]);
        expect(r.body.angles[14]).toEqual([14, 49.5, 10]);
        expect(r.body.angles[29]).toEqual([20, 49.5, 10]);
      });
    });

    describe('bad input', () => {
      test.each([
        [
          'series',
          'arm=arm1&field=temp%22)%20%7C%3E%20drop(columns%3A%5B%22_value%22%5D)',
          'field',
        ],
        ['series', 'arm=arm1%22%20or%20r.arm%20!%3D%20%22&field=temp', 'arm'],
        ['series', 'arm=arm1&field=temp&id=000%2C001%22', 'id'],
        ['alarms', 'arm=arm1&start=-1h%0A%7C%3E%20yield()', 'start'],
        ['tracking', 'arm=arm1&stop=2024-01-01T00%3A00%3A00Z%22', 'stop'],
        ['pose', 'arm=%F0%9F%A4%96', 'arm'],
        ['series', 'arm=arm1&field=temp&start=-40d', 'start'],
        ['alarms', 'arm=arm1&id=255', 'id'],
      ])('%s?%s → 400 naming %s', async (endpoint, qs, parameter) => {
        const r = await get(`/history/${endpoint}?${qs}`);
        expect(r.status).toBe(400);
        expect(r.body.parameter).toBe(parameter);
      });

      test('a hostile string that got past validation would still be one InfluxQL literal', async () => {
        if (language !== 'influxql') return;
        const { url, token, org, bucket } = influx();
        const reader = influxqlReader({ url, token, org, bucket, timeoutMs: 30_000 });
        const p = { ids: 'all' as const, field: 'temp' as const, startMs: T0, stopMs: T0 + 60_000 };
        // Spliced raw, these would match every arm (arm2's 99 °C too) or end the statement.
        expect(await reader.series({ ...p, arm: 'arm1\' OR "arm" != \'' }, '10s')).toEqual([]);
        expect(
          await reader.series(
            { ...p, arm: "x'; DROP DATABASE armtwin; --", ids: ["0' OR 'a'='a"] },
            '10s',
          ),
        ).toEqual([]);
        expect((await reader.series({ ...p, arm: 'arm1' }, '10s')).length).toBe(12);
      });
    });
  });

  describe('Flux literals', () => {
    test('a hostile string that got past validation would still be one Flux string literal', async () => {
      // If `arm` were spliced in raw, this would match every arm and return arm2's 99 °C too.
      const hostile = 'arm1" or r.arm != "';
      const q = seriesQuery(
        influx().bucket,
        { arm: hostile, ids: 'all', field: 'temp', startMs: T0, stopMs: T0 + 60_000 },
        '10s',
      );
      expect(await queryApi.collectRows(q)).toEqual([]);
      const drop = seriesQuery(
        influx().bucket,
        {
          arm: '") |> drop(columns: ["_value"]) //',
          ids: ['x" or true or "'],
          field: 'temp',
          startMs: T0,
          stopMs: T0 + 60_000,
        },
        '10s',
      );
      expect(await queryApi.collectRows(drop)).toEqual([]);
      // The honest query on the same range does see data: the empty answers above mean "no such arm".
      const honest = seriesQuery(
        influx().bucket,
        { arm: 'arm1', ids: 'all', field: 'temp', startMs: T0, stopMs: T0 + 60_000 },
        '10s',
      );
      expect((await queryApi.collectRows(honest)).length).toBe(12);
    });
  });
});
