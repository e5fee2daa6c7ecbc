/**
 * Keep-out zones written from the HUD through `armtwin up` (docs/protocol.md, "Keep-out
 * zones"): `PUT /api/robots/<name>/keep-out` with nonsense is refused with every reason, named by
 * zone and field, and the profile stays as it was; a good one is written into profile.json, the
 * running simulator takes it at once (announced again, retained) and refuses a raw frame into
 * the new zone. A profile file broken by hand leaves the arm stopped: every move refused.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { MODELS_DIR } from '@armtwin/sim';
import { freePorts } from '../helpers/services.ts';
import { startUpProcess, StatusWatcher, type Child } from './sim-helpers.ts';

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** armtwin5's servos 000–003 at 0°, −45°, −45°, −90°: the hand straight down into the table. */
const INTO_TABLE = '{#000P1500T0500!#001P1167T0500!#002P1167T0500!#003P0833T0500!}';

let up: Child;
let w: StatusWatcher;
let httpPort = 0;
let models = '';
const file = () => path.join(models, 'zone5', 'profile.json');

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-keep-out-'));
  fs.cpSync(path.join(MODELS_DIR, 'armtwin5'), path.join(models, 'zone5'), { recursive: true });
  const raw = JSON.parse(fs.readFileSync(file(), 'utf8'));
  fs.writeFileSync(file(), JSON.stringify({ ...raw, name: 'zone5' }));
  const [h = 0, m = 0] = await freePorts(2);
  httpPort = h;
  up = await startUpProcess(
    ['scripts/start.mjs'],
    ['--no-middleware', '--no-web', '--models', models, '--arms', 'arm1:zone5'],
    { httpPort, mqttPort: m },
  );
  w = await StatusWatcher.connect(`mqtt://127.0.0.1:${m}`, 'arm1');
  await w.client.subscribeAsync('arm/arm1/profile', { qos: 1 });
});

afterAll(async () => {
  await w?.close();
  await up?.stop('SIGKILL');
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

const put = async (body: string) => {
  const res = await fetch(`http://127.0.0.1:${httpPort}/api/robots/zone5/keep-out`, {
    method: 'PUT',
    headers: { 'content-type': 'application/json' },
    body,
  });
  return { status: res.status, body: (await res.json()) as { ok: boolean; errors?: string[] } };
};
const announcedZones = () => {
  const a = w.retained.get('arm/arm1/profile');
  return a ? (JSON.parse(a).profile.keepOut?.zones as unknown[] | undefined) : undefined;
};

test('zones with nonsense are refused, named by zone and field; the profile stays', async () => {
  const before = fs.readFileSync(file(), 'utf8');
  const bad = await put(
    JSON.stringify({
      zones: [
        { ...TABLE, max: [100, 150, 30] },
        { name: 'post', shape: 'cone' },
      ],
    }),
  );
  expect(bad.status).toBe(400);
  expect(bad.body.errors).toEqual([
    expect.stringMatching(/^keepOut\.zones\[0\] "table"\.max: must be above min on every axis/),
    expect.stringMatching(/^keepOut\.zones\[1\] "post"\.shape: must be one of/),
  ]);
  expect((await put('{nope')).body.errors).toEqual(['the request is not JSON']);
  expect(fs.readFileSync(file(), 'utf8')).toBe(before);
});

test('a table written from the HUD is in force at the simulator at once', async () => {
  const ok = await put(JSON.stringify({ zones: [TABLE] }));
  expect(ok).toMatchObject({ status: 200, body: { ok: true } });
  expect(JSON.parse(fs.readFileSync(file(), 'utf8')).keepOut).toEqual({ zones: [TABLE] });
  await w.until(() => (announcedZones()?.length === 1 ? true : undefined), 10_000, 'announced');
  expect(announcedZones()).toEqual([TABLE]);
  const from = w.items.length;
  await w.send(INTO_TABLE);
  const err = await w.frame((f) => f.type === 'controllerError', from);
  expect(err.frame).toMatchObject({ text: expect.stringMatching(/zone: hand in "table"/) });
});

test('a profile file broken by hand leaves the arm stopped: every move is refused', async () => {
  fs.writeFileSync(file(), fs.readFileSync(file(), 'utf8').replace('"table"', '""'));
  // Until the sim has read the file a harmless gripper move may run; then it is refused.
  let sentAt = 0;
  const refused = await w.until(
    () => {
      if (Date.now() - sentAt > 250) {
        sentAt = Date.now();
        void w.send('#005P1600T0100!');
      }
      return w.items.find(
        (i) => 'frame' in i && i.frame.type === 'controllerError' && /invalid/.test(i.frame.text),
      );
    },
    10_000,
    'the refusal',
  );
  expect(refused).toMatchObject({ frame: { text: 'zone: profile.json invalid' } });
});
