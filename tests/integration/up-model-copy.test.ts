/**
 * Model mode's copy of an arm (docs/protocol.md § Modes), through `armtwin up` in-process with a
 * users file (its embedded broker, the real HTTP route): `POST /api/arms/arm1/model` starts
 * `arm1-model` at the pose sent; the copy has the arm's limits and follows its zones (a zone
 * written after it started refuses a move into it), takes control claims like an arm, and
 * nothing sent to it reaches the real arm; a second POST puts it at another pose; DELETE stops
 * it. Bad bodies, unknown arms, viewers and missing log-ins are refused with the reason; an arm
 * id ending in `-model` is refused by `armtwin up`. On a real Mosquitto, a copy with nothing
 * sent to it stops by itself.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { loadUsers } from '@armtwin/auth';
import { MODELS_DIR } from '@armtwin/sim';
import { ModelCopies, startUp, type Up, type UpOptions } from '@armtwin/up';
import { REPO_ROOT, startMosquitto, type MosquittoService } from '../helpers/services.ts';
import { StatusWatcher } from './sim-helpers.ts';

const USERS_FILE = path.join(REPO_ROOT, 'deploy', 'users.example.json');
const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** armtwin5's servos 000–003 at 0°, −45°, −45°, −90°: the hand straight down into the table. */
const INTO_TABLE = '{#000P1500T0500!#001P1167T0500!#002P1167T0500!#003P0833T0500!}';
const COPY = 'arm1-model';

let models = '';
let up: Up;
let base = '';
let copy: StatusWatcher;
let arm: StatusWatcher;
let spy: MqttClient;
/** Everything on the real arm's control topics. */
const onArmControl: string[] = [];

const options = (o: Partial<UpOptions>): UpOptions => ({
  httpPort: 0,
  mqttPort: 0,
  mqttPortFallback: false,
  host: '127.0.0.1',
  armId: 'arm1',
  rate: 50,
  arms: [{ id: 'arm1', profile: 'zone5' }],
  influxUrl: '',
  buildWeb: false,
  middleware: false,
  env: {},
  users: loadUsers(USERS_FILE),
  tls: null,
  apiToken: '',
  modelsDir: models,
  say: () => {},
  onFirst: () => {},
  ...o,
});

const login = (user: string) => ({ username: user, password: `${user}-demo` });

async function call(method: string, arm: string, user: string | null, body?: string) {
  const headers: Record<string, string> = { 'content-type': 'application/json' };
  if (user)
    headers.authorization = `Basic ${Buffer.from(`${user}:${user}-demo`).toString('base64')}`;
  const res = await fetch(`${base}api/arms/${arm}/model`, {
    method,
    headers,
    ...(body === undefined ? {} : { body }),
  });
  return { status: res.status, body: (await res.json()) as Record<string, unknown> };
}
const post = (body: unknown, user = 'operator') => call('POST', 'arm1', user, JSON.stringify(body));

const holder = () => copy.retained.get(`arm/${COPY}/holder`);

/** Polls `f` until it gives a value (a condition met over HTTP, where no event says so). */
async function eventually<T>(f: () => Promise<T | undefined>, what: string): Promise<T> {
  const deadline = Date.now() + 10_000;
  for (;;) {
    const v = await f();
    if (v !== undefined) return v;
    if (Date.now() > deadline) throw new Error(`timed out waiting for ${what}`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

/** The copy's latest reported pulse of servo `id` after item `from`. */
const lastPulse = (w: StatusWatcher, id: number, from = 0) => w.positions(id, from).at(-1)?.[1];

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-model-copy-'));
  const dir = path.join(models, 'zone5');
  fs.cpSync(path.join(MODELS_DIR, 'armtwin5'), dir, { recursive: true });
  const raw = JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8'));
  fs.writeFileSync(path.join(dir, 'profile.json'), JSON.stringify({ ...raw, name: 'zone5' }));
  up = await startUp(options({}));
  base = up.url;
  copy = await StatusWatcher.connect(up.broker.url, COPY, login('viewer'));
  await copy.client.subscribeAsync([`arm/${COPY}/profile`, `arm/${COPY}/holder`], { qos: 1 });
  arm = await StatusWatcher.connect(up.broker.url, 'arm1', login('operator'));
  // The middleware's rights: the only role that reads an arm's control topics.
  spy = up.broker.connectInProcess({ name: 'spy', role: 'middleware' }, {});
  spy.on('message', (topic, payload) => onArmControl.push(`${topic} ${payload.toString()}`));
  await spy.subscribeAsync(['arm/arm1/control', 'arm/arm1/control/+'], { qos: 1 });
});

afterAll(async () => {
  await copy?.close();
  await arm?.close();
  await spy?.endAsync(true);
  await up?.stop();
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

test('POST starts the copy at the pose sent: online, reporting that pose', async () => {
  expect(await call('GET', 'arm1', 'viewer')).toEqual({
    status: 200,
    body: { ok: true, armId: COPY, running: false },
  });
  const started = await post({ pulses: { '0': 1800, '001': 1400 } });
  expect(started).toEqual({
    status: 201,
    body: { ok: true, armId: COPY, running: true, started: true, pulses: { 0: 1800, 1: 1400 } },
  });
  await copy.until(() => (copy.retained.get(`arm/${COPY}/online`) === '1' ? true : undefined));
  await copy.until(() =>
    lastPulse(copy, 0) === 1800 && lastPulse(copy, 1) === 1400 ? true : undefined,
  );
  expect((await call('GET', 'arm1', 'viewer')).body).toMatchObject({ running: true });
  // Its profile is the arm's, announced on its own topic.
  const announced = JSON.parse(copy.retained.get(`arm/${COPY}/profile`) ?? '{}');
  expect(announced.name).toBe('zone5');
});

test("the copy has the arm's limits and follows its zones; nothing reaches the real arm", async () => {
  const operator = await mqtt.connectAsync(up.broker.url, login('operator'));
  try {
    // A zone written after the copy started is in force on it too.
    const put = await fetch(`${base}api/robots/zone5/keep-out`, {
      method: 'PUT',
      headers: {
        'content-type': 'application/json',
        authorization: `Basic ${Buffer.from('operator:operator-demo').toString('base64')}`,
      },
      body: JSON.stringify({ zones: [TABLE] }),
    });
    expect(put.status).toBe(200);
    await copy.until(() => {
      const a = copy.retained.get(`arm/${COPY}/profile`);
      return a && JSON.parse(a).profile.keepOut?.zones?.length === 1 ? true : undefined;
    });
    const armBefore = lastPulse(arm, 0);
    // The operator claims the copy as it would claim an arm, then drives it.
    await operator.publishAsync(`arm/${COPY}/claim/operator`, 'take', { qos: 1 });
    await copy.until(() => (JSON.parse(holder() ?? '{}').user === 'operator' ? true : undefined));
    // Each command after a beat: the claim's lease holds while the test runs, however slowly.
    const drive = async (frames: string) => {
      await operator.publishAsync(`arm/${COPY}/claim/operator`, 'beat', { qos: 1 });
      await operator.publishAsync(`arm/${COPY}/control/operator`, frames, { qos: 1 });
    };
    const from = copy.items.length;
    await drive(INTO_TABLE);
    const zone = await copy.frame((f) => f.type === 'controllerError', from);
    expect(zone.frame).toMatchObject({ text: expect.stringMatching(/zone: hand in "table"/) });
    const next = copy.items.length;
    await drive('#005P1000T0100!');
    const limit = await copy.frame((f) => f.type === 'controllerError', next);
    expect(limit.frame).toMatchObject({ text: expect.stringMatching(/^limit 005 P1000 outside/) });
    // A move it may make, it makes; the real arm stays where it was and hears nothing.
    await drive('#000P1300T0100!');
    await copy.until(() => (lastPulse(copy, 0) === 1300 ? true : undefined));
    expect(onArmControl).toEqual([]);
    expect(lastPulse(arm, 0)).toBe(armBefore);
    await operator.publishAsync(`arm/${COPY}/claim/operator`, 'release', { qos: 1 });
  } finally {
    await operator.endAsync(true);
  }
});

test('POST again puts the running copy at the new pose; DELETE stops it', async () => {
  const again = await post({ pulses: { 0: 1200, 2: 1600 } });
  expect(again).toEqual({
    status: 200,
    body: { ok: true, armId: COPY, running: true, started: false, pulses: { 0: 1200, 2: 1600 } },
  });
  const from = copy.items.length;
  await copy.until(() =>
    lastPulse(copy, 0, from) === 1200 && lastPulse(copy, 2, from) === 1600 ? true : undefined,
  );
  expect(await call('DELETE', 'arm1', 'operator')).toEqual({
    status: 200,
    body: { ok: true, armId: COPY, running: false },
  });
  await copy.until(() => (copy.retained.get(`arm/${COPY}/online`) === '0' ? true : undefined));
  expect((await call('GET', 'arm1', 'viewer')).body).toMatchObject({ running: false });
  // The real arm is still there.
  expect(arm.retained.get('arm/arm1/online')).toBe('1');
});

test('bad bodies, unknown arms, viewers and missing log-ins get the reason', async () => {
  const unknown = await post({ pulses: { 9: 1500, 1: 1500 } });
  expect(unknown).toMatchObject({
    status: 400,
    body: { ok: false, errors: [expect.stringMatching(/pulses\.9: the arm has no servo 009/)] },
  });
  const nan = await post({ pulses: { 1: 'x' }, speed: 2 });
  expect(nan.status).toBe(400);
  expect(nan.body.errors).toEqual(
    expect.arrayContaining([
      expect.stringMatching(/^pulses\.1: a pulse width/),
      expect.stringMatching(/speed/),
    ]),
  );
  expect((await call('POST', 'arm1', 'operator', '{nope')).body).toEqual({
    ok: false,
    errors: ['the request is not JSON'],
  });
  expect(await call('POST', 'nosuch', 'operator', '')).toMatchObject({
    status: 404,
    body: { errors: [expect.stringMatching(/no arm "nosuch" to copy/)] },
  });
  expect((await call('GET', COPY, 'viewer')).status).toBe(404);
  expect(await post({}, 'viewer')).toMatchObject({
    status: 403,
    body: { errors: ['viewers may not change a robot'] },
  });
  expect((await call('DELETE', 'arm1', 'viewer')).status).toBe(403);
  expect((await call('GET', 'arm1', null)).status).toBe(401);
  expect((await call('POST', 'arm1', null, '{}')).status).toBe(401);
  // Nothing was started by any of them.
  expect((await call('GET', 'arm1', 'viewer')).body).toMatchObject({ running: false });
});

test('an arm up does not simulate has a copy when its announced profile is in the models', async () => {
  // A real arm behind a gateway announces its profile, retained, as its device.
  const device = up.broker.connectInProcess({ name: 'arm2', role: 'device', arm: 'arm2' }, {});
  try {
    await device.publishAsync('arm/arm2/profile', JSON.stringify({ name: 'zone5' }), {
      qos: 1,
      retain: true,
    });
    const w = await StatusWatcher.connect(up.broker.url, 'arm2-model', login('viewer'));
    try {
      // The announcement reaches up's own subscriber in its own time: ask until it is known.
      await eventually(
        async () => (await call('GET', 'arm2', 'viewer')).status === 200 || undefined,
        'arm2 known',
      );
      const started = await call(
        'POST',
        'arm2',
        'operator',
        JSON.stringify({ pulses: { 4: 1900 } }),
      );
      expect(started).toMatchObject({ status: 201, body: { armId: 'arm2-model', started: true } });
      await w.until(() => (lastPulse(w, 4) === 1900 ? true : undefined));
      expect((await call('DELETE', 'arm2', 'operator')).body).toMatchObject({ running: false });
    } finally {
      await w.close();
    }
  } finally {
    await device.publishAsync('arm/arm2/profile', '', { qos: 1, retain: true });
    await device.endAsync(true);
  }
});

test('armtwin up refuses an arm id ending in -model: it is reserved for copies', async () => {
  await expect(startUp(options({ arms: [{ id: 'lab-model', profile: 'zone5' }] }))).rejects.toThrow(
    'arm id "lab-model": ids ending in -model are reserved for model copies',
  );
});

test('on Mosquitto, a copy that nothing is sent to stops by itself', async () => {
  let broker: MosquittoService | undefined;
  let copies: ModelCopies | undefined;
  let w: StatusWatcher | undefined;
  try {
    broker = await startMosquitto();
    const url = broker.url;
    w = await StatusWatcher.connect(url, COPY);
    const said: string[] = [];
    copies = new ModelCopies(
      {
        source: (id) => (id === 'arm1' ? { profile: 'zone5', modelsDir: models } : undefined),
        connect: (_id, opts) => mqtt.connect(url, opts),
        onFirst: () => {},
        say: (m) => said.push(m),
      },
      { idleMs: 1000 },
    );
    await copies.start('arm1', new Map([[0, 1700]]));
    await w.until(() => (lastPulse(w!, 0) === 1700 ? true : undefined));
    await w.until(() => (w!.retained.get(`arm/${COPY}/online`) === '0' ? true : undefined));
    expect(copies.running('arm1')).toBe(false);
    await w.until(() => (said.some((m) => /idle/.test(m)) ? true : undefined));
  } finally {
    await copies?.stopAll();
    await w?.close();
    await broker?.dispose();
  }
});
