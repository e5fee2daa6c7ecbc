/**
 * Roles and log-ins on the embedded broker (`armtwin broker` / `npm start`): with the users file, every
 * client logs in and the roles are enforced by Aedes' hooks; MQTTS and WSS with a throwaway CA;
 * oversize packets refused; anonymous only on loopback.
 */
import https from 'node:https';
import mqtt from 'mqtt';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { startBroker, type Broker } from '@armtwin/broker';
import { loadUsers } from '@armtwin/auth';
import { makeTestCa, type TestCa } from '../helpers/tls.ts';
import {
  checkLogins,
  checkPublishes,
  checkSubscribes,
  checkWills,
  connector,
  password,
  USERS_FILE,
} from './auth-cases.ts';

let ca: TestCa;
let broker: Broker;
let server: https.Server;
let wssUrl = '';

beforeAll(async () => {
  ca = makeTestCa();
  broker = await startBroker({
    port: 0,
    users: loadUsers(USERS_FILE),
    tls: { cert: ca.cert, key: ca.key },
  });
  server = https.createServer({ cert: ca.cert, key: ca.key });
  broker.attach(server);
  await new Promise<void>((resolve) => server.listen(0, '127.0.0.1', resolve));
  const a = server.address();
  wssUrl = `wss://localhost:${typeof a === 'object' && a ? a.port : 0}/mqtt`;
});

afterAll(async () => {
  server?.closeAllConnections();
  await broker?.close();
  server?.close();
  ca?.dispose();
});

const mqtts = () => connector(`mqtts://localhost:${broker.port}`, { ca: ca.ca });

describe('roles on the embedded broker (MQTTS, trusting the test CA)', () => {
  test('log-ins: every user with its password; anonymous and wrong passwords refused', async () => {
    await checkLogins(mqtts());
    expect(broker.counters.refusedLogins).toBeGreaterThanOrEqual(3);
  });
  test('subscriptions follow the role table (denied = SUBACK 0x80, nothing delivered)', () =>
    checkSubscribes(mqtts(), { suback0x80: true, sharedSubscriptions: false }));
  test('publishes follow the role table (denied = never delivered)', () => checkPublishes(mqtts()));
  test("last wills: an operator's is published, a viewer's is not", () => checkWills(mqtts()));
});

describe('TLS', () => {
  test('mqtts:// without trusting the CA is refused', async () => {
    await expect(
      mqtt.connectAsync(`mqtts://localhost:${broker.port}`, {
        username: 'viewer',
        password: password('viewer'),
        reconnectPeriod: 0,
        connectTimeout: 5000,
      }),
    ).rejects.toThrow(/self[- ]signed|unable to verify|certificate/i);
  });

  test('wss:// /mqtt on the HTTPS port: works trusting the CA, refused otherwise', async () => {
    const c = await connector(wssUrl, { ca: ca.ca })('viewer');
    expect((await c.subscribeAsync('arm/+/status', { qos: 1 }))[0]!.qos).toBe(1);
    await c.endAsync(true);
    await expect(
      mqtt.connectAsync(wssUrl, {
        username: 'viewer',
        password: password('viewer'),
        reconnectPeriod: 0,
        connectTimeout: 5000,
      }),
    ).rejects.toThrow(/self[- ]signed|unable to verify|certificate/i);
  });
});

describe('oversize packets and in-process clients', () => {
  test('a packet over 64 KiB closes its sender and is not delivered; one under passes', async () => {
    const connect = mqtts();
    const mw = await connect('middleware');
    const got: number[] = [];
    mw.on('message', (_t, p) => got.push(p.length));
    await mw.subscribeAsync('arm/+/control/+', { qos: 1 });
    const op = await connect('operator');
    await op.publishAsync('arm/arm1/control/operator', Buffer.alloc(60_000, 0x20), { qos: 1 });
    const closed = new Promise<void>((r) => op.once('close', () => r()));
    op.publish('arm/arm1/control/operator', Buffer.alloc(70_000, 0x20), { qos: 1 });
    await closed;
    await new Promise((r) => setTimeout(r, 300));
    expect(got).toEqual([60_000]);
    expect(broker.counters.oversizePackets).toBe(1);
    op.end(true);
    await mw.endAsync(true);
  });

  test('an in-process client gets exactly its principal’s rights, with no password', async () => {
    const dev = broker.connectInProcess(
      { name: 'sim', role: 'device', arm: 'arm1' },
      { reconnectPeriod: 0 },
    );
    await new Promise((r) => dev.once('connect', r));
    const mw = await mqtts()('middleware');
    const got: string[] = [];
    mw.on('message', (t) => got.push(t));
    await mw.subscribeAsync('arm/+/status', { qos: 1 });
    await dev.publishAsync('arm/arm1/status', '$PNG:1!', { qos: 1 });
    dev.on('error', () => {});
    dev.publish('arm/arm2/status', '$PNG:2!', { qos: 1 });
    await new Promise((r) => setTimeout(r, 300));
    expect(got).toEqual(['arm/arm1/status']);
    dev.end(true);
    await mw.endAsync(true);
  });
});

describe('anonymous demo', () => {
  test('without a users file the broker refuses to listen beyond loopback', async () => {
    await expect(startBroker({ host: '0.0.0.0', port: 0 })).rejects.toThrow(/ARMTWIN_USERS/);
  });

  test('on loopback anonymous clients may do anything but $SYS', async () => {
    const b = await startBroker({ port: 0 });
    const c = await mqtt.connectAsync(b.url, { reconnectPeriod: 0 });
    expect((await c.subscribeAsync('#', { qos: 1 }))[0]!.qos).toBe(1);
    await c.endAsync(true);
    await b.close();
  });
});
