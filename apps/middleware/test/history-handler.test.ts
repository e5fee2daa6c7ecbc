/** The HTTP handler with a fake QueryApi: routing, status codes, and that 400s never query. */
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import type { QueryApi } from '@influxdata/influxdb-client';
import { afterAll, beforeAll, beforeEach, describe, expect, test } from 'vitest';
import { fluxReader } from '../src/history/flux-reader.ts';
import { createHistoryHandler } from '../src/history/handler.ts';

const NOW = Date.UTC(2024, 0, 1, 0, 0, 0);
const queries: string[] = [];
let reply: (q: string) => Record<string, unknown>[] = () => [];

const fakeQueryApi = {
  collectRows: async (q: unknown) => {
    queries.push(String(q));
    return reply(String(q));
  },
} as unknown as QueryApi;

const handler = createHistoryHandler({
  reader: fluxReader(fakeQueryApi, 'armtwin/autogen'),
  now: () => NOW,
});
let base = '';
const server = http.createServer((req, res) => {
  handler(req, res)
    .then((mine) => {
      if (!mine) res.writeHead(418).end('not mine');
    })
    .catch(() => res.writeHead(500).end());
});

beforeAll(async () => {
  await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
  base = `http://127.0.0.1:${(server.address() as AddressInfo).port}`;
});
afterAll(() => new Promise<void>((r) => server.close(() => r())));
beforeEach(() => {
  queries.length = 0;
  reply = () => [];
});

const get = async (path: string, init?: RequestInit) => {
  const res = await fetch(base + path, init);
  const text = await res.text();
  return {
    status: res.status,
    type: res.headers.get('content-type'),
    body: text ? JSON.parse(text) : undefined,
  };
};

describe('createHistoryHandler', () => {
  test('paths outside /history are not its own', async () => {
    expect((await fetch(`${base}/healthz`)).status).toBe(418);
    expect((await fetch(`${base}/historyx`)).status).toBe(418);
  });

  test('unknown endpoint 404, other methods 405', async () => {
    expect(await get('/history/nope?arm=a')).toMatchObject({ status: 404 });
    expect((await fetch(`${base}/history/series`, { method: 'POST' })).status).toBe(405);
  });

  test('series: window sized from the range, rows shaped per id', async () => {
    reply = () => [
      { _time: '2024-01-01T00:00:01Z', _value: 40.5, id: '001' },
      { _time: '2024-01-01T00:00:00.5Z', _value: 41, id: '000' },
      { _time: '2024-01-01T00:00:00.2Z', _value: 39, id: '001' },
    ];
    const r = await get('/history/series?arm=arm1&field=temp&start=-5m');
    expect(r.status).toBe(200);
    expect(r.type).toContain('application/json');
    expect(r.body).toEqual({
      arm: 'arm1',
      start: NOW - 300_000,
      stop: NOW,
      field: 'temp',
      every: '200ms',
      everyMs: 200,
      series: [
        { id: '000', times: [NOW + 500], values: [41] },
        { id: '001', times: [NOW + 200, NOW + 1000], values: [39, 40.5] },
      ],
    });
    expect(queries).toHaveLength(1);
    expect(queries[0]).toContain('every: duration(v: "200ms")');
  });

  test('a bad parameter is a 400 naming it, and nothing is queried', async () => {
    for (const [qs, parameter] of [
      ['arm=arm1&field=temp%22)%20%7C%3E%20drop(', 'field'],
      ['arm=arm1%22&field=temp', 'arm'],
      ['arm=arm1&field=temp&id=001%0A', 'id'],
      ['arm=arm1&field=temp&start=2024-01-01T00:00:00Z&stop=2023-12-01T00:00:00Z', 'start'],
      ['arm=arm1&field=temp&flux=yield()', 'flux'],
    ]) {
      const r = await get(`/history/series?${qs}`);
      expect(r.status).toBe(400);
      expect(r.body.parameter).toBe(parameter);
      expect(typeof r.body.error).toBe('string');
    }
    expect(queries).toEqual([]);
  });

  test('alarms: episodes from the reduced rows', async () => {
    reply = () => [
      { _time: '2024-01-01T00:00:00Z', _value: 59, _field: 'temp', id: '002' },
      { _time: '2024-01-01T00:00:01Z', _value: 61, _field: 'temp', id: '002' },
      { _time: '2024-01-01T00:00:02Z', _value: 58, _field: 'temp', id: '002' },
      { _time: '2024-01-01T00:00:03Z', _value: 6.4, _field: 'volt', id: '000' },
    ];
    const r = await get('/history/alarms?arm=arm1&start=-1h');
    expect(r.body.episodes).toEqual([
      {
        kind: 'temp-warning',
        arm: 'arm1',
        id: '002',
        start: NOW + 1000,
        end: NOW + 2000,
        peak: 61,
      },
      { kind: 'undervoltage', arm: 'arm1', id: '000', start: NOW + 3000, end: null, peak: 6.4 },
    ]);
    expect(r.body.truncated).toBe(false);
  });

  test('tracking: counts first, then commands and actual samples', async () => {
    reply = (q) => {
      if (q.includes('count()')) return [{ _value: 3, id: '001' }];
      if (q.includes('"command"'))
        return [{ _time: '2024-01-01T00:00:00Z', id: '001', angle: 10, ms: 0 }];
      return [
        { _time: '2024-01-01T00:00:00Z', _value: 9, id: '001' },
        { _time: '2024-01-01T00:00:01Z', _value: 12, id: '001' },
      ];
    };
    const r = await get(
      '/history/tracking?arm=arm1&start=2023-12-31T23:59:00Z&stop=2024-01-01T00:01:00Z',
    );
    expect(r.body).toMatchObject({
      thinnedEveryMs: null,
      joints: [{ id: '001', samples: 2, meanAbsError: 1.5, maxAbsError: 2 }],
    });
    expect(queries).toHaveLength(3);
  });

  test('pose: frames on the union of times, values held forward', async () => {
    reply = () => [
      { _time: '2024-01-01T00:00:01Z', _value: 1, id: '000' },
      { _time: '2024-01-01T00:00:02Z', _value: 2, id: '001' },
      { _time: '2024-01-01T00:00:03Z', _value: 3, id: '000' },
    ];
    const r = await get('/history/pose?arm=arm1&start=-1m');
    expect(r.body).toMatchObject({
      ids: ['000', '001'],
      times: [NOW + 1000, NOW + 2000, NOW + 3000],
      angles: [
        [1, null],
        [1, 2],
        [3, 2],
      ],
    });
  });

  test('an InfluxDB failure is a 502 with the reason', async () => {
    reply = () => {
      throw new Error('connect ECONNREFUSED');
    };
    const r = await get('/history/series?arm=arm1&field=volt');
    expect(r.status).toBe(502);
    expect(r.body.error).toContain('ECONNREFUSED');
  });
});
