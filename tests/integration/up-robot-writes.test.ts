/**
 * `armtwin up`'s writes to robot folders in the anonymous local demo (where anyone is an
 * operator; roles are covered by the e2e tests): a calibration with bad fields, for an unknown
 * robot, for a pulse servo, too big, or not JSON is refused with every reason and the profile is
 * left as it was; a good one rewrites it and keeps a backup. An import that is not a zip, holds
 * no URDF, or takes a name in use is refused with the reason.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, expect, test } from 'vitest';
import { MAX_CALIBRATION_REQUEST_BYTES } from '@armtwin/robot';
import { MODELS_DIR } from '@armtwin/sim';
import { freePorts } from '../helpers/services.ts';
import { startUpProcess, type Child } from './sim-helpers.ts';

let up: Child;
let httpPort = 0;
let models = '';
const file = () => path.join(models, 'bus5', 'profile.json');

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-writes-'));
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
  );
  raw.name = 'bus5';
  raw.servos[2] = { ...raw.servos[2], units: 'angle', min: -150, max: 150 };
  fs.mkdirSync(path.join(models, 'bus5'));
  fs.writeFileSync(file(), JSON.stringify(raw));
  const [h = 0, m = 0] = await freePorts(2);
  httpPort = h;
  up = await startUpProcess(
    ['scripts/start.mjs'],
    ['--no-middleware', '--no-web', '--models', models],
    { httpPort, mqttPort: m },
  );
});

afterAll(async () => {
  await up?.stop('SIGKILL');
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

async function send(method: string, url: string, body: BodyInit, type = 'application/json') {
  const res = await fetch(`http://127.0.0.1:${httpPort}${url}`, {
    method,
    headers: { 'content-type': type },
    body,
  });
  return { status: res.status, body: (await res.json()) as { ok: boolean; errors?: string[] } };
}
const calibrate = (body: unknown, robot = 'bus5') =>
  send('PUT', `/api/robots/${robot}/calibration`, JSON.stringify(body));
const elbow = { id: 2, polarity: -1, offset: 12.5, min: -40, max: 100 };

test('a bad calibration is refused with every reason, and the profile stays as it was', async () => {
  const before = fs.readFileSync(file(), 'utf8');
  const bad = await calibrate({ servos: [{ id: 2, polarity: 0, offset: 'x', min: 1 }] });
  expect(bad.status).toBe(400);
  expect(bad.body.errors!.join('\n')).toMatch(
    /servos\[0\]\.polarity[\s\S]*servos\[0\]\.offset[\s\S]*servos\[0\]\.max/,
  );
  expect((await calibrate({ servos: [elbow] }, 'nosuch')).status).toBe(404);
  const pulse = await calibrate({ servos: [{ ...elbow, id: 1 }] });
  expect(pulse).toMatchObject({
    status: 400,
    body: { errors: [expect.stringMatching(/only bus servos/)] },
  });
  const limits = await calibrate({ servos: [{ ...elbow, min: 100, max: -40 }] });
  expect(limits.body.errors!.join()).toMatch(/servos\[2\]\.min/);
  expect((await send('PUT', '/api/robots/bus5/calibration', '{nope')).body.errors).toEqual([
    'the request is not JSON',
  ]);
  const big = await send(
    'PUT',
    '/api/robots/bus5/calibration',
    ' '.repeat(MAX_CALIBRATION_REQUEST_BYTES + 1),
  );
  expect(big.status).toBe(413);
  expect(fs.readFileSync(file(), 'utf8')).toBe(before);
  expect(fs.readdirSync(path.dirname(file()))).toEqual(['profile.json']);
});

test('a good calibration rewrites the servo and keeps the old file', async () => {
  const before = fs.readFileSync(file(), 'utf8');
  const r = await calibrate({ servos: [elbow] });
  expect(r).toMatchObject({ status: 200, body: { ok: true } });
  const now = JSON.parse(fs.readFileSync(file(), 'utf8'));
  const { id, ...fields } = elbow;
  expect(id).toBe(2);
  expect(now.servos[2]).toMatchObject({ id: '002', units: 'angle', ...fields });
  const backups = fs.readdirSync(path.dirname(file())).filter((f) => f.endsWith('.bak'));
  expect(backups).toHaveLength(1);
  expect(fs.readFileSync(path.join(path.dirname(file()), backups[0]!), 'utf8')).toBe(before);
});

test('an import that is not a robot is refused with the reason', async () => {
  const notZip = await send('POST', '/api/robots/import', 'hello', 'application/zip');
  expect(notZip).toMatchObject({
    status: 400,
    body: { errors: [expect.stringMatching(/not a \.zip/)] },
  });
  // an empty zip (end of central directory only)
  const empty = new Uint8Array(22);
  new DataView(empty.buffer).setUint32(0, 0x06054b50, true);
  const noUrdf = await send('POST', '/api/robots/import', empty, 'application/zip');
  expect(noUrdf.status).toBe(400);
  const badName = await send('POST', '/api/robots/import?name=Bad%20Name', 'x', 'application/zip');
  expect(badName.body.errors![0]).toMatch(/name must be/);
  expect(fs.readdirSync(models)).toEqual(['bus5']);
});
