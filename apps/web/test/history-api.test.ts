import { describe, expect, it } from 'vitest';
import {
  errorText,
  HistoryApi,
  historyUrl,
  type Fetch,
} from '../src/ui/panels/History/historyApi.ts';

describe('history API client', () => {
  it('builds URLs with repeated ids and trims the base', () => {
    expect(
      historyUrl('http://h/api/', 'series', { arm: 'arm1', field: 'temp', start: 1, stop: 2 }),
    ).toBe('http://h/api/history/series?arm=arm1&field=temp&start=1&stop=2');
    expect(historyUrl('/api', 'pose', { arm: 'a b', id: ['000', '002'] })).toBe(
      '/api/history/pose?arm=a+b&id=000&id=002',
    );
  });

  it.each([
    [
      400,
      { error: 'arm must match', parameter: 'arm' },
      'The history API refused the request (parameter arm): arm must match',
    ],
    [
      503,
      { error: 'history needs storage: set INFLUX_URL' },
      'History is not available: history needs storage: set INFLUX_URL (HTTP 503).',
    ],
    [
      502,
      { error: 'InfluxDB query failed: x' },
      'The history database failed: InfluxDB query failed: x (HTTP 502).',
    ],
    [404, 'not found', 'No history API at this address (HTTP 404). Is the middleware running?'],
    [500, '', 'The history API answered HTTP 500.'],
  ])('HTTP %i %j → %s', (status, body, text) => {
    expect(errorText(status, body)).toBe(text);
  });

  const answer =
    (status: number, body: string): Fetch =>
    () =>
      Promise.resolve(new Response(body, { status }));

  it('answers data, or the error as text, and never throws', async () => {
    const ok = new HistoryApi({ base: '/api', fetch: answer(200, '{"episodes":[]}') });
    expect(await ok.get('alarms', { arm: 'a' })).toEqual({ ok: true, data: { episodes: [] } });
    const bad = new HistoryApi({
      base: '/api',
      fetch: answer(503, '{"error":"history needs storage: set INFLUX_URL"}'),
    });
    expect(await bad.get('alarms', { arm: 'a' })).toEqual({
      ok: false,
      error: 'History is not available: history needs storage: set INFLUX_URL (HTTP 503).',
    });
    const html = new HistoryApi({ base: '/api', fetch: answer(200, '<html>') });
    expect((await html.get('alarms', { arm: 'a' })).ok).toBe(false);
    const down = new HistoryApi({
      base: 'http://127.0.0.1:9/api',
      fetch: () => Promise.reject(new TypeError('Failed to fetch')),
    });
    expect(await down.get('alarms', { arm: 'a' })).toEqual({
      ok: false,
      error: 'The history API at http://127.0.0.1:9/api is unreachable: Failed to fetch',
    });
  });

  it('sends the extra headers', async () => {
    let seen: HeadersInit | undefined;
    const api = new HistoryApi({
      base: '/api',
      headers: { authorization: 'Bearer t' },
      fetch: (_url, init) => {
        seen = init?.headers;
        return Promise.resolve(new Response('{}'));
      },
    });
    await api.get('pose', { arm: 'a' });
    expect(seen).toMatchObject({ authorization: 'Bearer t', accept: 'application/json' });
  });
});
