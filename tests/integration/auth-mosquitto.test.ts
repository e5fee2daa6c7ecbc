/**
 * Roles and log-ins on Mosquitto 2.0: `armtwin deploy-mosquitto` turns deploy/users.example.json into
 * mosquitto.conf, passwd and acl; a real Mosquitto runs that configuration (with a throwaway
 * CA's certificate) and enforces the same role table as the embedded broker. Also: the sample
 * in deploy/mosquitto is what the generator writes, our `$7$` hashes are accepted by Mosquitto,
 * anonymous is refused on every listener, and max_packet_size holds.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import mqtt from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import type { ServiceProcess } from '../helpers/process.ts';
import { startDeployedMosquitto } from '../helpers/mosquitto.ts';
import { REPO_ROOT } from '../helpers/services.ts';
import { makeTestCa, type TestCa } from '../helpers/tls.ts';
import { ARMTWIN } from './sim-helpers.ts';
import {
  checkLogins,
  checkPublishes,
  checkSubscribes,
  checkWills,
  connector,
  password,
  readText,
  USERS_FILE,
} from './auth-cases.ts';

let ca: TestCa;
let svc: ServiceProcess;
let ports: number[] = [];

beforeAll(async () => {
  ca = makeTestCa();
  svc = await startDeployedMosquitto('mosquitto-deploy', USERS_FILE, ca);
  ports = svc.spec.ports;
});

afterAll(async () => {
  await svc?.dispose({ keepLogs: false });
  ca?.dispose();
});

const local = () => connector(`mqtt://127.0.0.1:${ports[0]}`);
const mqtts = () => connector(`mqtts://localhost:${ports[1]}`, { ca: ca.ca });

describe('the committed sample is what the generator writes', () => {
  test('deploy/mosquitto/{mosquitto.conf,passwd,acl} are up to date with users.example.json', () => {
    const out = fs.mkdtempSync(path.join(svc.spec.dir, 'sample-'));
    execFileSync(
      process.execPath,
      [
        ARMTWIN,
        'deploy-mosquitto',
        '--users',
        USERS_FILE,
        '--out',
        out,
        '--conf-dir',
        '/etc/mosquitto/armtwin',
      ],
      { cwd: REPO_ROOT, stdio: 'pipe' },
    );
    for (const f of ['mosquitto.conf', 'passwd', 'acl'])
      expect(readText(path.join(out, f)), f).toBe(
        readText(path.join(REPO_ROOT, 'deploy', 'mosquitto', f)),
      );
  });
});

describe('roles on Mosquitto (generated passwd + acl)', () => {
  test('log-ins: our $7$ hashes are accepted; anonymous and wrong passwords refused', async () => {
    await checkLogins(local());
    await checkLogins(mqtts());
  });
  test('subscriptions follow the role table (checked on delivery)', () =>
    checkSubscribes(mqtts(), { suback0x80: false, sharedSubscriptions: true }));
  test('publishes follow the role table', () => checkPublishes(mqtts()));
  test("last wills: an operator's is published, a viewer's is not", () => checkWills(mqtts()));
});

describe('TLS listeners', () => {
  test('mqtts:// and wss:// work trusting the CA, and are refused without it', async () => {
    const wss = `wss://localhost:${ports[2]}`;
    const c = await connector(wss, { ca: ca.ca })('viewer');
    expect((await c.subscribeAsync('arm/+/online', { qos: 1 }))[0]!.qos).toBe(1);
    await c.endAsync(true);
    for (const url of [`mqtts://localhost:${ports[1]}`, wss])
      await expect(
        mqtt.connectAsync(url, {
          username: 'viewer',
          password: password('viewer'),
          reconnectPeriod: 0,
          connectTimeout: 5000,
        }),
      ).rejects.toThrow(/self[- ]signed|unable to verify|certificate/i);
  });

  test('max_packet_size 65536: a bigger publish never arrives', async () => {
    const mw = await mqtts()('middleware');
    const got: number[] = [];
    mw.on('message', (_t, p) => got.push(p.length));
    await mw.subscribeAsync('arm/+/control/+', { qos: 1 });
    const op = await mqtts()('operator');
    op.on('error', () => {});
    await op.publishAsync('arm/arm1/control/operator', Buffer.alloc(60_000, 0x20), { qos: 1 });
    op.publish('arm/arm1/control/operator', Buffer.alloc(70_000, 0x20), { qos: 1 });
    await new Promise((r) => setTimeout(r, 800));
    expect(got).toEqual([60_000]);
    op.end(true);
    await mw.endAsync(true);
  });
});
