/**
 * Security in the middleware: the API token on /metrics and /history (not /healthz), oversize
 * messages refused and counted, hostile topics dropped and counted, the readers map bounded.
 */
import { EventEmitter } from 'node:events';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { describe, expect, test } from 'vitest';
import { hashPassword, LoginThrottle, parseUsers } from '@armtwin/auth';
import { loadConfig } from '../src/config.ts';
import { createHttpHandler, type HealthReport } from '../src/http.ts';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

/** The status the handler answers with (some answers come after an async log-in check). */
async function call(handler: ReturnType<typeof createHttpHandler>, url: string, auth?: string) {
  return (await answer(handler, url, auth)).status;
}

describe('API token', () => {
  const health = () => ({ ok: true }) as HealthReport;
  const history = async (_req: IncomingMessage, res: ServerResponse) => (
    res.writeHead(200).end(),
    true
  );

  test('with API_TOKEN: /metrics and /history need the bearer token; /healthz stays open', async () => {
    const h = createHttpHandler({ metrics: new Metrics(), health, history, apiToken: 's3cret' });
    expect(await call(h, '/healthz')).toBe(200);
    expect(await call(h, '/api/healthz')).toBe(200);
    expect(await call(h, '/metrics')).toBe(401);
    expect(await call(h, '/api/metrics', 'Bearer wrong')).toBe(401);
    expect(await call(h, '/api/metrics', 'Basic czNjcmV0')).toBe(401);
    expect(await call(h, '/history/series?arm=arm1')).toBe(401);
    expect(await call(h, '/metrics', 'Bearer s3cret')).toBe(200);
    expect(await call(h, '/api/history/series?arm=arm1', 'bearer s3cret')).toBe(200);
  });

  test('without it the API is open (the local demo)', async () => {
    const h = createHttpHandler({ metrics: new Metrics(), health, history });
    expect(await call(h, '/metrics')).toBe(200);
  });

  test('API_TOKEN and MAX_PAYLOAD_BYTES come from the environment', () => {
    const c = loadConfig({ API_TOKEN: 'abc', MAX_PAYLOAD_BYTES: '1024' });
    expect([c.apiToken, c.maxPayloadBytes]).toEqual(['abc', 1024]);
    expect(loadConfig({}).maxPayloadBytes).toBe(65536);
    expect(() => loadConfig({ API_TOKEN: 'a b' })).toThrow(/API_TOKEN/);
  });
});

/** Like `call`, for answers that come after an (async) log-in check: status and body. */
function answer(handler: ReturnType<typeof createHttpHandler>, url: string, auth?: string) {
  return new Promise<{ status: number; body: string; headers: Record<string, string> }>(
    (resolve) => {
      const req = {
        url,
        method: 'GET',
        headers: auth ? { authorization: auth } : {},
        socket: { remoteAddress: '10.0.0.5' },
      } as unknown as IncomingMessage;
      const out = { status: 0, body: '', headers: {} as Record<string, string> };
      const res = Object.assign(new EventEmitter(), {
        headersSent: false,
        writeHead(status: number, headers: Record<string, string> = {}) {
          out.status = status;
          out.headers = headers;
          return res;
        },
        end(body?: string) {
          out.body = body ?? '';
          resolve(out);
          return res;
        },
      });
      handler(req, res as unknown as ServerResponse);
    },
  );
}

describe('users file (ARMTWIN_USERS): the HUD logs in against the middleware', () => {
  const health = () => ({ ok: true }) as HealthReport;
  const history = async (_req: IncomingMessage, res: ServerResponse) => (
    res.writeHead(200).end('history'),
    true
  );
  const users = parseUsers(
    JSON.stringify({
      users: [
        { name: 'ana', role: 'operator', password: hashPassword('pw-ana', { iterations: 10 }) },
        { name: 'vic', role: 'viewer', password: hashPassword('pw-vic', { iterations: 10 }) },
      ],
    }),
  );
  const basic = (u: string, p: string) => `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
  const handler = (apiToken = '') =>
    createHttpHandler({
      metrics: new Metrics(),
      health,
      history,
      apiToken,
      logins: new LoginThrottle(users, { perUser: 2, perAddress: 10, windowS: 60, lockoutS: 300 }),
    });

  test('/whoami: the role for a log-in, 401 without one', async () => {
    const h = handler();
    expect(await answer(h, '/api/whoami', basic('ana', 'pw-ana'))).toMatchObject({
      status: 200,
      body: JSON.stringify({ name: 'ana', role: 'operator' }),
    });
    expect((await answer(h, '/whoami', basic('vic', 'pw-vic'))).body).toContain('"viewer"');
    expect((await answer(h, '/whoami')).status).toBe(401);
    expect((await answer(h, '/whoami', basic('ana', 'nope'))).status).toBe(401);
  });

  test('a user’s log-in opens /history and /metrics, as the token does; nothing else does', async () => {
    const h = handler('s3cret');
    expect(await answer(h, '/api/history/series?arm=arm1', basic('vic', 'pw-vic'))).toMatchObject({
      status: 200,
      body: 'history',
    });
    expect((await answer(h, '/metrics', basic('vic', 'pw-vic'))).status).toBe(200);
    expect((await answer(h, '/metrics', 'Bearer s3cret')).status).toBe(200);
    expect((await answer(h, '/metrics', basic('vic', 'wrong'))).status).toBe(401);
    expect((await answer(h, '/metrics')).status).toBe(401);
  });

  test('with users and no token, /history still needs a log-in; /healthz stays open', async () => {
    const h = handler();
    expect((await answer(h, '/history/series?arm=arm1')).status).toBe(401);
    expect(await call(h, '/healthz')).toBe(200);
  });

  test('failed log-ins lock the address out: 429 with Retry-After, even for the right password', async () => {
    const h = handler();
    for (let i = 0; i < 3; i++) await answer(h, '/whoami', basic('ana', 'guess'));
    const locked = await answer(h, '/whoami', basic('ana', 'pw-ana'));
    expect(locked.status).toBe(429);
    expect(Number(locked.headers['retry-after'])).toBeGreaterThan(290);
    expect((await answer(h, '/history/series?arm=arm1', basic('ana', 'pw-ana'))).status).toBe(429);
  });

  test('ARMTWIN_USERS comes from the environment', () => {
    expect(loadConfig({ ARMTWIN_USERS: '/etc/armtwin/users.json' }).usersFile).toBe(
      '/etc/armtwin/users.json',
    );
  });
});

describe('Ingest bounds', () => {
  test('an oversize message is refused whole and counted once', () => {
    const m = new Metrics();
    const ingest = new Ingest(m, undefined, { maxPayloadBytes: 100 });
    expect(ingest.handle('arm/arm1/status', '#000P1500!'.repeat(11), 0)).toEqual([]);
    expect(m.rejected).toEqual({ oversize: 1 });
    expect(ingest.handle('arm/arm1/status', '#000P1500!'.repeat(10), 0)).toHaveLength(10);
  });

  test('hostile topics never reach line protocol: dropped as bad-topic', () => {
    const m = new Metrics();
    const ingest = new Ingest(m);
    for (const arm of ['a"b', 'a,b', 'a b', 'a\nb', 'a\\b', 'a=b', 'A1', ''])
      expect(ingest.handle(`arm/${arm}/status`, '#000P1500!', 0)).toEqual([]);
    expect(m.rejected).toEqual({ 'bad-topic': 8 });
  });

  test('the readers map is bounded: the oldest is forgotten', () => {
    const m = new Metrics();
    const ingest = new Ingest(m, undefined, { maxReaders: 3 });
    for (let i = 0; i < 10; i++) ingest.handle(`arm/arm${i}/status`, '#000P15', 0);
    expect((ingest as unknown as { readers: Map<string, unknown> }).readers.size).toBe(3);
  });
});
