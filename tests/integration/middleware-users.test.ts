/**
 * A Mosquitto deployment has no `armtwin up` to tell the HUD its role: the middleware does it.
 * Run with ARMTWIN_USERS (the same users file the Mosquitto configuration was generated from)
 * and API_TOKEN, the real middleware process on real Mosquitto and influxd answers `/whoami`
 * for the HUD's log-in and lets a user's log-in read `/history` and `/metrics`; a bad users
 * file stops it at start-up with the variable named.
 */
import { spawn } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { expect, test } from 'vitest';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { REPO, tempDir } from '../../apps/middleware/test/support/harness.ts';
import { password, USERS_FILE } from './auth-cases.ts';

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-users', () => ({ mqttUrl: broker().url, influx: influx() }));
const TOKEN = 'mw-users-token-42';

const basic = (u: string, p = password(u)) =>
  `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;

test('the middleware answers /whoami and takes a user’s log-in for /history and /metrics', async () => {
  const mw = await mws.spawn({
    env: {
      ARMTWIN_USERS: USERS_FILE,
      API_TOKEN: TOKEN,
    },
  });
  const base = `http://127.0.0.1:${mw.port}`;
  const get = (p: string, auth?: string) =>
    fetch(`${base}${p}`, { headers: auth ? { authorization: auth } : {} });

  const who = await get('/api/whoami', basic('operator'));
  expect(who.status).toBe(200);
  expect(await who.json()).toEqual({ name: 'operator', role: 'operator' });
  expect(await (await get('/whoami', basic('viewer'))).json()).toEqual({
    name: 'viewer',
    role: 'viewer',
  });
  expect((await get('/whoami')).status).toBe(401);
  expect((await get('/whoami', basic('viewer', 'wrong'))).status).toBe(401);

  const series = '/api/history/series?arm=arm1&field=pwm&id=000&start=-5m';
  expect((await get(series)).status).toBe(401);
  expect((await get(series, basic('viewer'))).status).toBe(200);
  expect((await get(series, `Bearer ${TOKEN}`)).status).toBe(200);
  expect((await get('/metrics', basic('middleware'))).status).toBe(200);
  expect((await get('/healthz')).status).toBe(200);
});

test('a bad users file stops the middleware at start-up, naming ARMTWIN_USERS', async () => {
  const bad = path.join(tempDir('mw-users-bad'), 'users.json');
  fs.writeFileSync(bad, JSON.stringify({ users: [{ name: 'x', role: 'root', password: 'pw' }] }));
  const child = spawn(
    process.execPath,
    ['--import', 'tsx', path.join(REPO, 'apps', 'middleware', 'src', 'main.ts')],
    {
      cwd: REPO,
      env: { ...process.env, ARMTWIN_USERS: bad, MQTT_URL: broker().url, PORT: '0' },
      stdio: ['ignore', 'pipe', 'pipe'],
    },
  );
  let out = '';
  child.stdout.on('data', (d: Buffer) => (out += d.toString()));
  child.stderr.on('data', (d: Buffer) => (out += d.toString()));
  const code = await new Promise<number | null>((r) => child.once('exit', r));
  expect(code).toBe(2);
  expect(out).toContain('ARMTWIN_USERS');
  expect(out).toMatch(/role/);
  fs.rmSync(path.dirname(bad), { recursive: true, force: true });
});
