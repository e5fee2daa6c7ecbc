/**
 * `armtwin up` serves robot folders from disk at request time: a folder written into the
 * models folder after start-up is served at once (no HUD rebuild), each file with its content
 * type; a missing model file is a 404, never the HUD's index.html; nothing outside is served.
 */
import fs from 'node:fs';
import http from 'node:http';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { freePorts } from '../helpers/services.ts';
import { startUpProcess, type Child } from './sim-helpers.ts';

let up: Child;
let httpPort = 0;
let models = '';
const base = () => `http://127.0.0.1:${httpPort}`;

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-models-'));
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

/** A raw GET, so that `..` and `%2e%2e` reach the server as written. */
function rawGet(pathname: string): Promise<{ status: number; body: string }> {
  return new Promise((resolve, reject) => {
    http
      .get({ host: '127.0.0.1', port: httpPort, path: pathname }, (res) => {
        let body = '';
        res.on('data', (c: Buffer) => (body += c.toString()));
        res.on('end', () => resolve({ status: res.statusCode ?? 0, body }));
      })
      .on('error', reject);
  });
}

describe('armtwin up: /models/ from disk', () => {
  test('a robot folder written after start-up is served at once, with content types', async () => {
    const dir = path.join(models, 'newbot');
    fs.mkdirSync(path.join(dir, 'meshes'), { recursive: true });
    fs.writeFileSync(path.join(dir, 'newbot.urdf'), '<robot name="newbot"/>');
    fs.writeFileSync(path.join(dir, 'profile.json'), '{"format":"armtwin-profile/1"}');
    fs.writeFileSync(path.join(dir, 'meshes', 'a.stl'), 'solid a\nendsolid a\n');
    fs.writeFileSync(path.join(dir, 'meshes', 'b.obj'), 'v 0 0 0\n');
    fs.writeFileSync(path.join(dir, 'meshes', 'c.dae'), '<COLLADA/>');
    const expected: [string, RegExp, string][] = [
      ['newbot.urdf', /^application\/xml/, '<robot name="newbot"/>'],
      ['profile.json', /^application\/json/, '{"format":"armtwin-profile/1"}'],
      ['meshes/a.stl', /^model\/stl/, 'solid a\nendsolid a\n'],
      ['meshes/b.obj', /^model\/obj/, 'v 0 0 0\n'],
      ['meshes/c.dae', /^model\/vnd\.collada\+xml/, '<COLLADA/>'],
    ];
    for (const [file, type, body] of expected) {
      const res = await fetch(`${base()}/models/newbot/${file}`);
      expect(res.status, file).toBe(200);
      expect(res.headers.get('content-type'), file).toMatch(type);
      expect(await res.text(), file).toBe(body);
    }
  });

  test('the shipped robots are still served from public/models', async () => {
    const res = await fetch(`${base()}/models/armtwin5/profile.json`);
    expect(res.status).toBe(200);
    expect(((await res.json()) as { name: string }).name).toBe('armtwin5');
  });

  test('a missing model file is a 404, not the HUD page', async () => {
    const res = await fetch(`${base()}/models/newbot/meshes/missing.stl`);
    expect(res.status).toBe(404);
    expect(await res.text()).not.toContain('<html');
    expect((await fetch(`${base()}/models/nobot/nobot.urdf`)).status).toBe(404);
  });

  test('no path traversal out of the models folders', async () => {
    fs.writeFileSync(path.join(path.dirname(models), 'armtwin-secret.txt'), 'secret');
    try {
      for (const p of [
        '/models/..%2farmtwin-secret.txt',
        '/models/%2e%2e%2f%2e%2e%2fpackage.json',
        '/models/newbot/..%2f..%2f..%2fpackage.json',
      ]) {
        const res = await rawGet(p);
        expect(res.status, p).toBeGreaterThanOrEqual(400);
        expect(res.body, p).not.toContain('secret');
        expect(res.body, p).not.toContain('"workspaces"');
      }
    } finally {
      fs.rmSync(path.join(path.dirname(models), 'armtwin-secret.txt'), { force: true });
    }
  });
});
