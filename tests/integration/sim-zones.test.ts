/**
 * Keep-out zones at the simulator over a real Mosquitto (docs/protocol.md, "Keep-out zones"):
 * `armtwin sim --models <dir>` with armtwin5 and a table declared in its profile announces the
 * zone with the profile, and refuses what would take the arm through the table when it comes
 * past any page: a raw pulse group on `arm/{id}/control` (`$ERR:group rejected: zone: …`), a
 * `$KMS` (`$KMS:25!`) and a motion request (`unreachable`, code 25). Nothing moves.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { REPO_ROOT } from '../helpers/services.ts';
import { useMosquitto } from '../helpers/use-services.ts';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

const ARM = 'zonetest';
const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** armtwin5's servos 000–003 at 0°, −45°, −45°, −90°: the hand straight down into the table. */
const INTO_TABLE = '{#000P1500T0500!#001P1167T0500!#002P1167T0500!#003P0833T0500!}';

const broker = useMosquitto();
let models = '';
let sim: Child;
let w: StatusWatcher;
let fb: MqttClient;
const feedback: { id: string; status: string; code: number; message: string }[] = [];
/** The sim's control events (arm/{id}/audit): a refusal by a zone is part of the record. */
const audits: { by: string; kind: string; detail: string }[] = [];

beforeAll(async () => {
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-zones-'));
  const dir = path.join(models, 'armtwin5');
  fs.cpSync(path.join(REPO_ROOT, 'public/models/armtwin5'), dir, { recursive: true });
  const profile = JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8')) as object;
  fs.writeFileSync(
    path.join(dir, 'profile.json'),
    JSON.stringify({ ...profile, keepOut: { zones: [TABLE] } }),
  );
  const url = broker().url;
  w = await StatusWatcher.connect(url, ARM);
  fb = await mqtt.connectAsync(url);
  fb.on('message', (t, payload) =>
    (t.endsWith('/audit') ? audits : feedback).push(JSON.parse(payload.toString())),
  );
  await fb.subscribeAsync([`arm/${ARM}/feedback`, `arm/${ARM}/audit`], { qos: 1 });
  await w.client.subscribeAsync(`arm/${ARM}/profile`, { qos: 1 });
  sim = armtwin(['sim', '--mqtt', url, '--arm', ARM, '--rate', '50', '--models', models]);
  await w.until(
    () => (w.retained.get(`arm/${ARM}/online`) === '1' ? true : undefined),
    30_000,
    'online 1',
  );
});

afterAll(async () => {
  await sim?.stop('SIGKILL');
  await w?.close();
  await fb?.endAsync(true);
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

/** The sim's clock now: the `$TIM` of a ping's echo. */
async function simNow(): Promise<number> {
  const seq = Math.floor(Math.random() * 1e9);
  const from = w.items.length;
  await w.send(`$PNG:${seq}!`);
  return (await w.frame((f) => f.type === 'ping' && f.seq === seq, from)).time!;
}

/** Servo `id`'s reported pulses from sim time `after` on, once there are samples a second later. */
async function pulsesAfter(id: number, after: number): Promise<number[]> {
  const samples = await w.until(() => {
    const s = w.positions(id).filter(([t]) => t > after);
    return s.length > 0 && s[s.length - 1]![0] > after + 1000 ? s : undefined;
  }, 10_000);
  return samples.map(([, p]) => p);
}

describe('keep-out zones at the simulator', () => {
  test('the profile announced on arm/{id}/profile carries the table', async () => {
    const announced = await w.until(() => w.retained.get(`arm/${ARM}/profile`), 10_000, 'profile');
    expect(JSON.parse(announced).profile.keepOut.zones).toEqual([TABLE]);
  });

  test('a raw pulse group through the table is refused with $ERR and the arm does not move', async () => {
    const from = w.items.length;
    await w.send(INTO_TABLE);
    const err = await w.frame((f) => f.type === 'controllerError', from);
    expect(err.frame).toMatchObject({
      type: 'controllerError',
      text: expect.stringMatching(/^group rejected: zone: hand in "table"( on the way)?$/),
    });
    const t = await simNow();
    for (const id of [1, 2, 3]) expect(new Set(await pulsesAfter(id, t))).toEqual(new Set([1500]));
    const refusal = await w.until(
      () => audits.find((e) => e.kind === 'refused-keep-out'),
      10_000,
      'audit event',
    );
    expect(refusal).toMatchObject({ by: '' });
    expect(refusal.detail).toMatch(/^a client on a plain topic: .*"table"/);
  });

  test('$KMS into the table is $KMS:25!, above it $KMS:0!', async () => {
    let from = w.items.length;
    await w.send('$KMS:250,0,10,500!');
    expect((await w.frame((f) => f.type === 'kmsResult', from)).frame).toMatchObject({ code: 25 });
    from = w.items.length;
    await w.send('$KMS:250,0,120,500!');
    expect((await w.frame((f) => f.type === 'kmsResult', from)).frame).toMatchObject({ code: 0 });
  });

  test('a motion request through the table is unreachable, code 25, naming the zone', async () => {
    const id = `z${Date.now()}`;
    await fb.publishAsync(
      `arm/${ARM}/request`,
      JSON.stringify({
        id,
        mode: 'cartesian',
        targets: ['home', { x: 250, y: 0, z: 10 }],
        execute: true,
      }),
      { qos: 1 },
    );
    const f = await w.until(() => feedback.find((x) => x.id === id), 10_000, 'feedback');
    expect(f).toMatchObject({ status: 'unreachable', code: 25 });
    expect(f.message).toMatch(/^targets\[1\]: .*into zone "table"$/);
  });

  test('a zone file with nonsense in it: the sim says which zone and field, and does not start', async () => {
    const bad = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-zones-bad-'));
    try {
      const dir = path.join(bad, 'armtwin5');
      fs.cpSync(path.join(models, 'armtwin5'), dir, { recursive: true });
      const profile = JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8')) as object;
      const zones = [
        { name: 'table', shape: 'box', min: [150, -150, -20], max: [100, 150, 'top'] },
      ];
      fs.writeFileSync(
        path.join(dir, 'profile.json'),
        JSON.stringify({ ...profile, keepOut: { zones } }),
      );
      const arm = 'zonebad';
      const child = armtwin(['sim', '--mqtt', broker().url, '--arm', arm, '--models', bad]);
      const code = await new Promise<number | null>((resolve) => child.proc.once('exit', resolve));
      expect(code).not.toBe(0);
      expect(child.output()).toContain('keepOut.zones[0] "table".max[2]: must be a finite number');
    } finally {
      fs.rmSync(bad, { recursive: true, force: true });
    }
  });
});
