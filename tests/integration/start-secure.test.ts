/**
 * `npm start` outside the local demo: with ARMTWIN_USERS and a TLS certificate the embedded
 * broker takes log-ins only, over MQTTS and WSS (/mqtt on the HTTPS port); the in-process
 * arm and middleware work with their roles; /api needs the API token or a user's password;
 * the demo camera (`--camera testsrc`, real ffmpeg) is served over HTTPS/WSS and the in-process
 * middleware records it, trusting the up's own certificate (its file holds the chain to the test
 * CA, as a file for a private CA does); and without a users file `up` refuses to listen beyond
 * loopback.
 */
import fs from 'node:fs';
import path from 'node:path';
import https from 'node:https';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freePorts } from '../helpers/services.ts';
import { makeTestCa, type TestCa } from '../helpers/tls.ts';
import { useInflux } from '../helpers/use-services.ts';
import { connector, password, USERS_FILE } from './auth-cases.ts';
import { runNode, StatusWatcher, type Child } from './sim-helpers.ts';

const influx = useInflux();
const TOKEN = 'test-token-0123456789';
let ca: TestCa;
let up: Child;
let httpPort = 0;
let mqttPort = 0;

async function waitFor(child: Child, text: string) {
  const deadline = Date.now() + 60_000;
  while (!child.output().includes(text)) {
    if (Date.now() > deadline || child.proc.exitCode !== null)
      throw new Error(`no "${text}" from armtwin up:\n${child.output()}`);
    await new Promise((r) => setTimeout(r, 100));
  }
}

beforeAll(async () => {
  ca = makeTestCa();
  [httpPort = 0, mqttPort = 0] = await freePorts(2);
  // the certificate with its chain: what the up's own camera recording trusts
  const chain = path.join(ca.dir, 'chain.crt');
  fs.writeFileSync(chain, Buffer.concat([ca.cert, ca.ca]));
  up = runNode(
    [
      'scripts/start.mjs',
      '--no-web',
      '--camera',
      'testsrc',
      '--port',
      String(httpPort),
      '--mqtt-port',
      String(mqttPort),
    ],
    {
      ARMTWIN_USERS: USERS_FILE,
      ARMTWIN_TLS_CERT: chain,
      ARMTWIN_TLS_KEY: ca.keyFile,
      API_TOKEN: TOKEN,
      INFLUX_URL: influx().url,
      INFLUX_BUCKET: influx().bucket,
      SPOOL_DIR: `${ca.dir}/spool`,
      CAMERA_DIR: `${ca.dir}/cameras`,
      CAMERA_SEGMENT_S: '1',
    },
  );
  await waitFor(up, 'armtwin is running');
  await waitFor(up, 'middleware: running');
});

afterAll(async () => {
  await up?.stop('SIGINT');
  ca?.dispose();
});

function get(path: string, auth?: string): Promise<number> {
  return new Promise((resolve, reject) => {
    https
      .get(
        {
          host: 'localhost',
          port: httpPort,
          path,
          ca: ca.ca,
          headers: auth ? { authorization: auth } : {},
        },
        (res) => {
          res.resume();
          resolve(res.statusCode ?? 0);
        },
      )
      .on('error', reject);
  });
}

function getJson(path: string, auth: string): Promise<unknown> {
  return new Promise((resolve, reject) => {
    https
      .get(
        { host: 'localhost', port: httpPort, path, ca: ca.ca, headers: { authorization: auth } },
        (res) => {
          let body = '';
          res.on('data', (d: Buffer) => (body += d.toString()));
          res.on('end', () => resolve(JSON.parse(body)));
        },
      )
      .on('error', reject);
  });
}

describe('armtwin up with ARMTWIN_USERS and TLS', () => {
  test('says log-ins are required and prints an https URL', () => {
    expect(up.output()).toContain('log-in required');
    expect(up.output()).toContain(`open https://127.0.0.1:${httpPort}/`);
  });

  test('MQTTS: anonymous refused; a viewer sees arm1 online and streaming', async () => {
    await expect(connector(`mqtts://localhost:${mqttPort}`, { ca: ca.ca })(null)).rejects.toThrow(
      /Not authorized/,
    );
    const w = await StatusWatcher.connect(`mqtts://localhost:${mqttPort}`, 'arm1', {
      ca: ca.ca,
      username: 'viewer',
      password: password('viewer'),
    });
    await w.until(
      () => (w.retained.get('arm/arm1/online') === '1' ? true : undefined),
      10_000,
      'online 1',
    );
    await w.until(() => (w.positions(0).length >= 3 ? true : undefined), 10_000, 'state samples');
    await w.close();
  });

  test('WSS /mqtt on the HTTPS port: an operator pings arm1 and gets the echo', async () => {
    const w = await StatusWatcher.connect(`wss://localhost:${httpPort}/mqtt`, 'arm1', {
      ca: ca.ca,
      username: 'operator',
      password: password('operator'),
    });
    const from = w.items.length;
    // An operator writes its own control topic (docs/protocol.md § Control), not the plain one.
    await w.client.publishAsync('arm/arm1/control/operator', '$PNG:4242!', { qos: 1 });
    await w.frame((f) => f.type === 'ping' && f.seq === 4242, from);
    await w.close();
  });

  test('/api: healthz open; metrics need the token or a password', async () => {
    expect(await get('/api/healthz')).toBe(200);
    expect(await get('/api/metrics')).toBe(401);
    expect(await get('/api/history/series?arm=arm1')).toBe(401);
    expect(await get('/api/metrics', `Bearer ${TOKEN}`)).toBe(200);
    expect(await get('/api/metrics', 'Bearer nope')).toBe(401);
    const basic = (u: string, p: string) => `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
    expect(await get('/api/metrics', basic('viewer', password('viewer')))).toBe(200);
    expect(await get('/api/metrics', basic('viewer', 'wrong'))).toBe(401);
  });

  test('/api/whoami tells the HUD its role (401 without a log-in)', async () => {
    const basic = (u: string) => `Basic ${Buffer.from(`${u}:${password(u)}`).toString('base64')}`;
    expect(await get('/api/whoami')).toBe(401);
    expect(await getJson('/api/whoami', basic('viewer'))).toEqual({
      name: 'viewer',
      role: 'viewer',
    });
    expect(await getJson('/api/whoami', basic('arm1'))).toEqual({
      name: 'arm1',
      role: 'device',
      arm: 'arm1',
    });
  });

  test("the demo camera over WSS is recorded by the in-process middleware, trusting the up's own certificate", async () => {
    const viewer = `Basic ${Buffer.from(`viewer:${password('viewer')}`).toString('base64')}`;
    const list = () =>
      getJson('/api/arms/arm1/cameras/demo/segments', viewer) as Promise<{
        segments?: { name: string }[];
      }>;
    const deadline = Date.now() + 30_000;
    let segments: { name: string }[] = [];
    while (segments.length < 2 && Date.now() < deadline) {
      segments = (await list()).segments ?? [];
      if (segments.length < 2) await new Promise((r) => setTimeout(r, 250));
    }
    expect(segments.map((x) => path.extname(x.name))).toEqual(segments.map(() => '.mp4'));
    const said = up
      .output()
      .split('\n')
      .filter((l) => l.includes('camera recording'));
    expect(segments.length, said.join('\n')).toBeGreaterThanOrEqual(2);
    expect(up.output()).not.toContain('certificate');
  });

  // Last in this file: it locks 127.0.0.1 out for the `middleware` user for 5 minutes.
  test('failed log-ins: past 20 wrong passwords a minute, that user is locked out from this address, over MQTTS and /api', async () => {
    const connect = connector(`mqtts://localhost:${mqttPort}`, { ca: ca.ca });
    const basic = (u: string, p: string) => `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
    for (let i = 0; i < 21; i++)
      await expect(connect('middleware', { password: 'guess' })).rejects.toThrow(/Not authorized/);
    // The right password is refused now too, unchecked; /api says so with 429 and Retry-After.
    await expect(connect('middleware')).rejects.toThrow(/Not authorized/);
    expect(await get('/api/whoami', basic('middleware', password('middleware')))).toBe(429);
    // One log-in step for the whole API: every route says "locked out" alike.
    expect(await get('/api/metrics', basic('middleware', password('middleware')))).toBe(429);
    // Another user from the same address is not affected.
    await (await connect('viewer')).endAsync(true);
    expect(await getJson('/api/whoami', basic('viewer', password('viewer')))).toEqual({
      name: 'viewer',
      role: 'viewer',
    });
    expect(up.output()).toContain('login-locked-out');
  });
});

test('without a users file, up refuses a non-loopback host', async () => {
  const [p1 = 0, p2 = 0] = await freePorts(2);
  const bad = runNode([
    'scripts/start.mjs',
    '--no-web',
    '--no-middleware',
    '--host',
    '0.0.0.0',
    '--port',
    String(p1),
    '--mqtt-port',
    String(p2),
  ]);
  const code = await new Promise<number | null>((r) => bad.proc.once('exit', r));
  expect(code).not.toBe(0);
  expect(bad.output()).toMatch(/refusing anonymous MQTT on 0\.0\.0\.0.*ARMTWIN_USERS/);
});
