/**
 * The History panel's episodes client: what it sends for each action, and the text it gives
 * the panel when the middleware refuses (its own reason), has no storage, or is unreachable;
 * the recording time's wording.
 */
import { describe, expect, test } from 'vitest';
import { EpisodesApi, elapsed } from '../src/ui/panels/History/episodesApi.ts';

const mark = { startMs: 1, stopMs: null, task: 'pick', by: 'ana', discarded: false };

function api(status: number, body: unknown, sent: { url: string; init?: RequestInit }[] = []) {
  return new EpisodesApi({
    base: '/api/',
    headers: { authorization: 'Basic x' },
    fetch: async (url, init) => {
      sent.push({ url, init });
      return new Response(JSON.stringify(body), { status });
    },
  });
}

describe('episodes client', () => {
  test('an action is POSTed as JSON to the arm’s route, with the log-in; the mark comes back', async () => {
    const sent: { url: string; init?: RequestInit }[] = [];
    const r = await api(201, { ok: true, episode: mark }, sent).act('so101', {
      action: 'cut',
      task: 'wave',
      from: 1,
      to: 2,
    });
    expect(r).toEqual({ ok: true, data: mark });
    expect(sent[0]!.url).toBe('/api/arms/so101/episodes');
    expect(sent[0]!.init).toMatchObject({
      method: 'POST',
      body: '{"action":"cut","task":"wave","from":1,"to":2}',
      headers: { authorization: 'Basic x', 'content-type': 'application/json' },
    });
    expect(await api(200, { ok: true, episodes: [mark] }).list('so101')).toEqual({
      ok: true,
      data: [mark],
    });
  });

  test('a refusal says the middleware’s reason; no storage and no API say so', async () => {
    expect(
      await api(409, { ok: false, errors: ['no episode is recording'] }).act('a', {
        action: 'stop',
      }),
    ).toEqual({ ok: false, error: 'Refused (HTTP 409): no episode is recording' });
    expect(
      await api(503, { ok: false, errors: ['episodes need storage: set INFLUX_URL'] }).list('a'),
    ).toEqual({ ok: false, error: 'Refused (HTTP 503): episodes need storage: set INFLUX_URL' });
    const down = new EpisodesApi({
      base: '/api',
      fetch: () => Promise.reject(new Error('connection refused')),
    });
    expect(await down.list('a')).toEqual({
      ok: false,
      error: 'The episodes API at /api is unreachable: connection refused',
    });
  });

  test('the recording time: m:ss, then h:mm:ss', () => {
    expect([elapsed(0), elapsed(61_999), elapsed(3_725_000), elapsed(-5)]).toEqual([
      '0:00',
      '1:01',
      '1:02:05',
      '0:00',
    ]);
  });
});
