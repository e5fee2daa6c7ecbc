/**
 * A deployment without `armtwin up`: Mosquitto, `armtwin sim --models DIR` and the middleware
 * (MODELS_DIR=DIR, ARMTWIN_USERS), all real processes. The middleware's HTTP API saves a
 * calibration and a keep-out zone into the robot folders for an operator (a viewer, or no
 * log-in, is refused and nothing changes), serves the saved profile at /models/ for the page, and
 * the arm's controller puts the zone in force at once: it announces it and refuses a raw frame
 * into it. Model copies need `armtwin up`: the
 * middleware says so (501).
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { REPO_ROOT } from '../helpers/services.ts';
import { useInflux, useMosquitto } from '../helpers/use-services.ts';
import { useMiddlewares } from '../helpers/use-middlewares.ts';
import { password, USERS_FILE } from './auth-cases.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** armtwin5's servos 000–003 at 0°, −45°, −45°, −90°: the hand straight down into the table. */
const INTO_TABLE = '{#000P1500T0500!#001P1167T0500!#002P1167T0500!#003P0833T0500!}';
const ELBOW = { id: 2, polarity: -1, offset: 12.5, min: -40, max: 100 };

const broker = useMosquitto();
const influx = useInflux();
const mws = useMiddlewares('mw-robots', () => ({ mqttUrl: broker().url, influx: influx() }));
let models = '';
let sim: Child;
let w: StatusWatcher;
let base = '';
const profileFile = (name: string) => path.join(models, name, 'profile.json');

/** armtwin5 as robot `name`, `change`d. */
function copyRobot(name: string, change: (raw: Record<string, unknown>) => void = () => {}) {
  fs.cpSync(path.join(REPO_ROOT, 'public/models/armtwin5'), path.join(models, name), {
    recursive: true,
  });
  const raw = JSON.parse(fs.readFileSync(profileFile(name), 'utf8')) as Record<string, unknown>;
  change(raw);
  fs.writeFileSync(profileFile(name), JSON.stringify({ ...raw, name }));
}

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-mw-robots-'));
  copyRobot('zone5');
  // A bus servo to calibrate (the simulated arm keeps its pulse servos).
  copyRobot('bus5', (raw) => {
    const servos = raw.servos as Record<string, unknown>[];
    servos[2] = { ...servos[2], units: 'angle', min: -150, max: 150 };
  });
  const url = broker().url;
  w = await StatusWatcher.connect(url, 'arm1');
  await w.client.subscribeAsync('arm/arm1/profile', { qos: 1 });
  sim = armtwin(
    ['sim', '--mqtt', url, '--arm', 'arm1', '--rate', '50'].concat([
      '--models',
      models,
      '--profile',
      'zone5',
    ]),
  );
  const mw = await mws.spawn({ env: { ARMTWIN_USERS: USERS_FILE, MODELS_DIR: models } });
  base = `http://127.0.0.1:${mw.port}`;
  await w.until(
    () => (w.retained.get('arm/arm1/online') === '1' ? true : undefined),
    30_000,
    'online 1',
  );
});

afterAll(async () => {
  await sim?.stop('SIGKILL');
  await w?.close();
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

const basic = (u: string) => `Basic ${Buffer.from(`${u}:${password(u)}`).toString('base64')}`;

async function send(method: string, url: string, body: string, user?: string) {
  const res = await fetch(`${base}${url}`, {
    method,
    headers: {
      'content-type': 'application/json',
      ...(user ? { authorization: basic(user) } : {}),
    },
    body,
  });
  return { status: res.status, body: (await res.json()) as { ok: boolean; errors?: string[] } };
}
const announcedZones = () => {
  const a = w.retained.get('arm/arm1/profile');
  return a ? (JSON.parse(a).profile.keepOut?.zones as unknown[] | undefined) : undefined;
};

test('only an operator changes a robot: no log-in 401, a viewer 403, the files unchanged', async () => {
  const before = fs.readFileSync(profileFile('zone5'), 'utf8');
  const zones = JSON.stringify({ zones: [TABLE] });
  expect(await send('PUT', '/robots/zone5/keep-out', zones)).toMatchObject({
    status: 401,
    body: { ok: false, errors: ['log in as an operator'] },
  });
  expect(await send('PUT', '/api/robots/zone5/keep-out', zones, 'viewer')).toMatchObject({
    status: 403,
    body: { ok: false, errors: ['viewers may not change a robot'] },
  });
  expect(fs.readFileSync(profileFile('zone5'), 'utf8')).toBe(before);
});

test('an operator saves a calibration through the middleware; the old file is kept', async () => {
  const before = fs.readFileSync(profileFile('bus5'), 'utf8');
  const r = await send(
    'PUT',
    '/api/robots/bus5/calibration',
    JSON.stringify({ servos: [ELBOW] }),
    'operator',
  );
  expect(r).toMatchObject({ status: 200, body: { ok: true } });
  const { id, ...fields } = ELBOW;
  expect(id).toBe(2);
  const now = JSON.parse(fs.readFileSync(profileFile('bus5'), 'utf8'));
  expect(now.servos[2]).toMatchObject({ id: '002', units: 'angle', ...fields });
  const backups = fs.readdirSync(path.join(models, 'bus5')).filter((f) => f.endsWith('.bak'));
  expect(backups.map((b) => fs.readFileSync(path.join(models, 'bus5', b), 'utf8'))).toEqual([
    before,
  ]);
});

test('a keep-out zone saved through the middleware is in force at the simulator at once', async () => {
  const bad = await send(
    'PUT',
    '/api/robots/zone5/keep-out',
    '{"zones":[{"shape":"cone"}]}',
    'operator',
  );
  expect(bad.status).toBe(400);
  expect(bad.body.errors![0]).toMatch(/^keepOut\.zones\[0\]/);

  const ok = await send(
    'PUT',
    '/api/robots/zone5/keep-out',
    JSON.stringify({ zones: [TABLE] }),
    'operator',
  );
  expect(ok).toMatchObject({ status: 200, body: { ok: true } });
  expect(JSON.parse(fs.readFileSync(profileFile('zone5'), 'utf8')).keepOut).toEqual({
    zones: [TABLE],
  });
  // The page reads the robot from the middleware's /models/ (proxied as /api/ is): the saved zone.
  const served = await fetch(`${base}/models/zone5/profile.json`);
  expect(((await served.json()) as { keepOut: unknown }).keepOut).toEqual({ zones: [TABLE] });
  await w.until(() => (announcedZones()?.length === 1 ? true : undefined), 15_000, 'announced');
  expect(announcedZones()).toEqual([TABLE]);
  const from = w.items.length;
  await w.send(INTO_TABLE);
  const err = await w.frame((f) => f.type === 'controllerError', from);
  expect(err.frame).toMatchObject({ text: expect.stringMatching(/zone: hand in "table"/) });
});

test('model copies need armtwin up: the middleware answers 501 and says why', async () => {
  const r = await send('POST', '/api/arms/arm1/model', '', 'operator');
  expect(r.status).toBe(501);
  expect(r.body.errors![0]).toMatch(/armtwin up/);
});
