/**
 * The one HTTP API on a real node:http server: the router's answers (with and without `/api`,
 * 405 with the methods a route takes, paths it does not know left to the server), the
 * middleware's routes while it is not running (503, saying so), and the parts a server may lack
 * (no model-copy host: 501, saying why). Robot writes on disk: tests/integration.
 */
import fs from 'node:fs';
import http from 'node:http';
import type { AddressInfo } from 'node:net';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { hashPassword, LoginThrottle, parseUsers } from '@armtwin/auth';
import { createApi, type ApiService } from '../src/index.ts';

let server: http.Server;
let base = '';
let models = '';
let service: ApiService | null = null;
const onFirst: string[] = [];

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-api-'));
  const api = createApi({
    auth: { logins: null, apiToken: '', anonymous: 'loopback' },
    service: () => service,
    modelDirs: [models],
    modelCopies: null,
    onFirst: (kind) => onFirst.push(kind),
  });
  server = http.createServer((req, res) => {
    if (!api.handle(req, res)) res.writeHead(418).end('not the API');
  });
  await new Promise<void>((r) => server.listen(0, '127.0.0.1', r));
  base = `http://127.0.0.1:${(server.address() as AddressInfo).port}`;
});

afterAll(async () => {
  await new Promise((r) => server.close(r));
  fs.rmSync(models, { recursive: true, force: true });
});

const call = async (method: string, url: string, body?: string) => {
  const res = await fetch(`${base}${url}`, { method, ...(body ? { body } : {}) });
  const text = await res.text();
  return { status: res.status, allow: res.headers.get('allow'), text };
};

test('paths answer with and without /api; other paths are left to the server', async () => {
  expect((await call('PUT', '/api/robots/nosuch/keep-out', '{}')).status).toBe(404);
  expect(JSON.parse((await call('PUT', '/robots/nosuch/calibration', '{}')).text)).toEqual({
    ok: false,
    errors: ['no robot "nosuch"'],
  });
  expect((await call('GET', '/api/robots')).status).toBe(418);
  expect((await call('GET', '/index.html')).status).toBe(418);
});

test('a method a route does not take: 405 with the ones it does', async () => {
  expect(await call('GET', '/api/robots/x/calibration')).toMatchObject({
    status: 405,
    allow: 'PUT',
  });
  expect(await call('GET', '/api/robots/import')).toMatchObject({ status: 405, allow: 'POST' });
  expect(await call('POST', '/api/metrics')).toMatchObject({ status: 405, allow: 'GET, HEAD' });
  expect(await call('PUT', '/api/arms/arm1/model')).toMatchObject({
    status: 405,
    allow: 'GET, POST, DELETE',
  });
});

test('without the middleware its routes say so (503); with it they answer', async () => {
  service = null;
  for (const url of ['/api/healthz', '/api/metrics', '/api/history/series?arm=arm1']) {
    const r = await call('GET', url);
    expect(r.status).toBe(503);
    expect(JSON.parse(r.text)).toMatchObject({ ok: false, error: 'the middleware is not running' });
  }
  service = { health: () => ({ ok: true }), metrics: () => 'up 1\n', history: null };
  expect((await call('GET', '/healthz')).status).toBe(200);
  expect((await call('GET', '/metrics')).text).toBe('up 1\n');
  expect(JSON.parse((await call('GET', '/history/series')).text)).toEqual({
    error: 'history needs storage: set INFLUX_URL',
  });
});

test('without a users file /whoami has nothing to tell (404) where anonymous is not the demo', async () => {
  expect((await call('GET', '/api/whoami')).status).toBe(404);
});

test('no model-copy host: 501, naming armtwin up, counted', async () => {
  const r = await call('POST', '/api/arms/arm1/model');
  expect(r.status).toBe(501);
  expect(JSON.parse(r.text).errors[0]).toMatch(/armtwin up/);
  expect(onFirst).toContain('model:refused:host');
});

test('with a users file a refused read never carries a Basic challenge (no browser log-in dialog over the HUD)', async () => {
  const users = parseUsers(
    JSON.stringify({
      users: [{ name: 'vic', role: 'viewer', password: hashPassword('pw', { iterations: 10 }) }],
    }),
  );
  const api = createApi({
    auth: { logins: new LoginThrottle(users), apiToken: '', anonymous: 'anywhere' },
    service: () => ({ health: () => ({ ok: true }), metrics: () => 'up 1\n', history: null }),
    modelDirs: [],
    modelCopies: null,
    onFirst: () => {},
  });
  const srv = http.createServer((req, res) => void api.handle(req, res));
  await new Promise<void>((r) => srv.listen(0, '127.0.0.1', r));
  const url = `http://127.0.0.1:${(srv.address() as AddressInfo).port}/api/metrics`;
  const refused = await fetch(url);
  expect(refused.status).toBe(401);
  expect(refused.headers.get('www-authenticate')).toBe('Bearer realm="armtwin"');
  const viewer = await fetch(url, {
    headers: { authorization: `Basic ${Buffer.from('vic:pw').toString('base64')}` },
  });
  expect(await viewer.text()).toBe('up 1\n');
  await new Promise((r) => srv.close(r));
});

test('robot folders are served from the models folders at /models/, nothing outside them', async () => {
  fs.mkdirSync(path.join(models, 'r1'));
  fs.writeFileSync(path.join(models, 'r1', 'profile.json'), '{"name":"r1"}');
  expect(await call('GET', '/models/r1/profile.json')).toMatchObject({
    status: 200,
    text: '{"name":"r1"}',
  });
  expect((await call('GET', '/models/r1/none.stl')).status).toBe(404);
  // Sent as written (a URL would resolve the dots itself).
  const escape = await new Promise<number>((resolve, reject) =>
    http
      .get(
        {
          host: '127.0.0.1',
          port: new URL(base).port,
          path: '/models/r1/%2e%2e/%2e%2e/etc/passwd',
        },
        (res) => {
          res.resume();
          resolve(res.statusCode ?? 0);
        },
      )
      .on('error', reject),
  );
  expect(escape).toBe(403);
});

test('episodes: GET lists and POST marks through the middleware; without storage 503', async () => {
  service = { health: () => ({ ok: true }), metrics: () => '', history: null };
  expect(await call('GET', '/api/arms/arm1/episodes')).toMatchObject({ status: 503 });
  expect(await call('PUT', '/api/arms/arm1/episodes')).toMatchObject({
    status: 405,
    allow: 'GET, POST',
  });
  const asked: unknown[] = [];
  service.episodes = {
    list: async (arm, from, to) => (asked.push([arm, from, to]), [{ startMs: 1 }]),
    act: async (arm, body, by) => (
      asked.push([arm, body, by]),
      { status: 201, body: { ok: true } }
    ),
  };
  const listed = await call('GET', '/api/arms/arm1/episodes?from=2026-11-27T08:00:00Z');
  expect(JSON.parse(listed.text)).toEqual({ ok: true, episodes: [{ startMs: 1 }] });
  expect(await call('POST', '/api/arms/arm1/episodes', '{"action":"stop"}')).toMatchObject({
    status: 201,
  });
  expect(asked).toEqual([
    ['arm1', Date.UTC(2026, 10, 27, 8), undefined],
    ['arm1', { action: 'stop' }, 'anonymous'],
  ]);
  const bad = [
    await call('POST', '/api/arms/arm1/episodes', 'not json'),
    await call('GET', '/api/arms/arm1/episodes?to=yesterday'),
    await call('GET', '/api/arms/Bad_Arm/episodes'),
    await call('POST', '/api/arms/arm1/episodes', 'x'.repeat(5000)),
  ];
  expect(bad.map((r) => [r.status, JSON.parse(r.text).errors[0]])).toEqual([
    [400, 'the body is not JSON'],
    [400, 'from and to are ISO 8601 times'],
    [400, 'not an arm id: Bad_Arm'],
    [413, 'body over 4096 bytes'],
  ]);
  expect(asked).toHaveLength(2);
});
