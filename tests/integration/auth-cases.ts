/**
 * One table of who-may-do-what cases (SECURITY.md's roles), replayed against the embedded
 * Aedes broker (auth-embedded.test.ts) and against Mosquitto running the configuration
 * generated from the same users file (auth-mosquitto.test.ts): both brokers must agree.
 *
 * A publish counts as allowed when a user entitled to read the topic receives it. Mosquitto
 * drops a denied publish silently; Aedes closes the publisher's connection: either way it is
 * never delivered, which is what the table asserts.
 */
import fs from 'node:fs';
import path from 'node:path';
import mqtt, { type IClientOptions, type MqttClient } from 'mqtt';
import { expect } from 'vitest';
import { REPO_ROOT } from '../helpers/services.ts';

export const USERS_FILE = path.join(REPO_ROOT, 'deploy', 'users.example.json');
/** The sample file's passwords (deploy/README.md): `<name>-demo`. */
export const password = (user: string) => `${user}-demo`;
export const USERS = ['viewer', 'operator', 'arm1', 'arm2', 'middleware', 'admin'] as const;
export type User = (typeof USERS)[number];

/**
 * [user, subscription, probe topic, delivered]: after the user subscribes, a message published
 * on the probe topic (by a user allowed to) reaches it or not. Aedes refuses a subscription
 * outside the role (SUBACK 0x80); Mosquitto 2.0's acl_file grants every SUBSCRIBE and checks
 * read access on each delivery. Either way only what the role may read is delivered.
 */
export const SUBSCRIBE_CASES: [User, string, string, boolean][] = [
  ['viewer', 'arm/+/status', 'arm/arm1/status', true],
  ['viewer', 'arm/+/online', 'arm/arm1/online', true],
  ['viewer', 'arm/+/operator', 'arm/arm1/operator', true],
  ['viewer', 'arm/arm1/sim/faults', 'arm/arm1/sim/faults', true],
  ['viewer', 'arm/+/profile', 'arm/arm2/profile', true],
  ['viewer', 'arm/+/feedback', 'arm/arm1/feedback', true],
  ['viewer', 'arm/+/camera/+', 'arm/arm1/camera/front', true],
  ['operator', 'arm/arm1/camera/+', 'arm/arm1/camera/front', true],
  ['arm1', 'arm/arm1/camera/+', 'arm/arm1/camera/front', false],
  ['viewer', 'arm/+/camera/+/calibration', 'arm/arm1/camera/front/calibration', true],
  ['viewer', 'arm/+/control/+', 'arm/arm1/control/operator', false],
  ['viewer', 'arm/+/holder', 'arm/arm1/holder', true],
  ['viewer', 'arm/+/audit', 'arm/arm1/audit', true],
  ['viewer', 'arm/+/alert', 'arm/arm1/alert', true],
  ['viewer', 'arm/+/claim/+', 'arm/arm1/claim/operator', false],
  ['viewer', 'arm/arm1/sim', 'arm/arm1/sim', false],
  ['viewer', 'arm/#', 'arm/arm1/control/operator', false],
  ['viewer', '#', 'arm/arm1/request', false],
  ['operator', 'arm/arm1/status', 'arm/arm1/status', true],
  ['operator', 'arm/+/operator', 'arm/arm1/operator', true],
  ['operator', 'arm/+/control/+', 'arm/arm1/control/operator', false],
  ['operator', 'arm/+/request', 'arm/arm1/request', false],
  ['arm1', 'arm/arm1/control/+', 'arm/arm1/control/operator', true],
  ['arm1', 'arm/arm1/claim/+', 'arm/arm1/claim/operator', true],
  ['arm1', 'arm/arm1/override/+', 'arm/arm1/override/admin', true],
  ['arm1', 'arm/arm1/operator', 'arm/arm1/operator', true],
  ['arm1', 'arm/arm1/sim', 'arm/arm1/sim', true],
  ['arm1', 'arm/arm1/request', 'arm/arm1/request', true],
  ['arm1', 'arm/arm2/control/+', 'arm/arm2/control/operator', false],
  ['arm1', 'arm/+/control/+', 'arm/arm2/control/operator', false],
  ['arm1', 'arm/arm1/status', 'arm/arm1/status', false],
  ['arm1', '#', 'arm/arm2/sim', false],
  ['middleware', 'arm/+/status', 'arm/arm2/status', true],
  ['middleware', 'arm/+/control/+', 'arm/arm1/control/operator', true],
  ['middleware', 'arm/+/audit', 'arm/arm1/audit', true],
  ['middleware', 'arm/+/profile', 'arm/arm1/profile', true],
  ['middleware', '$share/armtwin/arm/+/status', 'arm/arm1/status', true],
  ['middleware', '$share/armtwin/arm/+/control/+', 'arm/arm2/control/operator', true],
  // its Foxglove server watches with the middleware's account (docs/foxglove.md)
  ['middleware', 'arm/+/holder', 'arm/arm1/holder', true],
  ['middleware', 'arm/+/alert', 'arm/arm1/alert', true],
  ['middleware', 'arm/+/camera/+', 'arm/arm1/camera/front', true],
  ['middleware', 'arm/+/feedback', 'arm/arm1/feedback', true],
  ['middleware', 'arm/+/claim/+', 'arm/arm1/claim/operator', false],
  ['middleware', 'arm/+/online', 'arm/arm1/online', false],
  ['middleware', '#', 'arm/arm1/operator', false],
];

export const PUBLISH_CASES: [User, string, boolean][] = [
  ['viewer', 'arm/arm1/control', false],
  ['viewer', 'arm/arm1/operator', false],
  ['viewer', 'arm/arm1/status', false],
  // One operator at a time (docs/protocol.md § Control): a user's own control and claim topics
  // only; the plain control topic, and anyone else's, are no operator's.
  ['operator', 'arm/arm1/control', false],
  ['operator', 'arm/arm1/control/operator', true],
  ['operator', 'arm/arm1/control/admin', false],
  ['operator', 'arm/arm1/claim/operator', true],
  ['operator', 'arm/arm1/claim/admin', false],
  ['operator', 'arm/arm1/override/operator', false],
  ['operator', 'arm/arm1/request/operator', true],
  ['operator', 'arm/arm1/request/admin', false],
  ['operator', 'arm/arm1/holder', false],
  ['admin', 'arm/arm1/override/admin', true],
  ['admin', 'arm/arm1/control/admin', true],
  ['admin', 'arm/arm1/override/operator', false],
  ['arm1', 'arm/arm1/holder', true],
  ['arm1', 'arm/arm1/audit', true],
  ['arm1', 'arm/arm1/control/operator', false],
  ['operator', 'arm/arm1/operator', true],
  ['operator', 'arm/arm1/request', true],
  ['operator', 'arm/arm1/sim', true],
  ['operator', 'arm/arm1/status', false],
  ['operator', 'arm/arm1/online', false],
  ['arm1', 'arm/arm1/status', true],
  ['arm1', 'arm/arm1/online', true],
  ['arm1', 'arm/arm1/sim/faults', true],
  ['arm1', 'arm/arm1/profile', true],
  ['arm1', 'arm/arm1/feedback', true],
  ['arm1', 'arm/arm1/camera/front', true],
  ['arm1', 'arm/arm2/camera/front', false],
  ['viewer', 'arm/arm1/camera/front', false],
  ['operator', 'arm/arm1/camera/front', false],
  ['operator', 'arm/arm1/camera/front/calibration', true],
  ['viewer', 'arm/arm1/camera/front/calibration', false],
  ['arm1', 'arm/arm1/camera/front/calibration', false],
  ['arm1', 'arm/arm2/status', false],
  ['arm1', 'arm/arm2/online', false],
  ['arm1', 'arm/arm1/control', false],
  ['arm2', 'arm/arm2/status', true],
  ['middleware', 'arm/arm1/status', false],
  ['middleware', 'arm/arm1/control', false],
  // The thermal watch's early warnings: the middleware's alone.
  ['middleware', 'arm/arm1/alert', true],
  ['operator', 'arm/arm1/alert', false],
  ['arm1', 'arm/arm1/alert', false],
];

/** Who reads each topic in the publish cases. */
function readerFor(topic: string): User {
  const [, arm, ...rest] = topic.split('/');
  const kind = rest.join('/');
  if (kind === 'status' || kind === 'control' || kind.startsWith('control/')) return 'middleware';
  if (/^(claim|override|request)\//.test(kind)) return arm as User;
  if (kind === 'sim' || kind === 'request') return arm as User;
  return 'viewer';
}

export type Connect = (user: User | null, opts?: IClientOptions) => Promise<MqttClient>;

/** mqtt.js connect as a user (null = anonymous), with no reconnects. */
export function connector(url: string, base: IClientOptions = {}): Connect {
  return (user, opts = {}) =>
    mqtt.connectAsync(url, {
      reconnectPeriod: 0,
      connectTimeout: 5000,
      ...base,
      ...(user ? { username: user, password: password(user) } : {}),
      ...opts,
    });
}

export async function checkLogins(connect: Connect): Promise<void> {
  for (const u of USERS) await (await connect(u)).endAsync(true);
  await expect(connect(null)).rejects.toThrow(/Not authorized|Bad username/i);
  await expect(connect('operator', { password: 'wrong' })).rejects.toThrow(
    /Not authorized|Bad username/i,
  );
  await expect(connect('nobody' as User, { password: 'x' })).rejects.toThrow(
    /Not authorized|Bad username/i,
  );
}

/** Who may publish each probe topic. */
function writerFor(topic: string): User {
  const [, arm, ...rest] = topic.split('/');
  const kind = rest.join('/');
  // A per-user topic is its user's to write (docs/protocol.md § Control).
  if (/^(control|claim|override|request)\//.test(kind)) return rest[1] as User;
  // The thermal model's early warnings are the middleware's (docs/protocol.md § A thermal model).
  if (kind === 'alert') return 'middleware';
  // A camera's calibration is an operator's to write; the rest of the arm's topics its device's.
  return ['control', 'operator', 'request', 'sim'].includes(kind) || kind.endsWith('/calibration')
    ? 'operator'
    : (arm as User);
}

/** Subscribes each case's user; publishes each probe; checks what was delivered to whom. */
export async function checkSubscribes(
  connect: Connect,
  o: { suback0x80: boolean; sharedSubscriptions: boolean },
): Promise<void> {
  // Aedes 1.x has no shared subscriptions: `$share/…` is only tried on Mosquitto.
  const cases = SUBSCRIBE_CASES.filter(
    ([, f]) => o.sharedSubscriptions || !f.startsWith('$share/'),
  );
  const received = cases.map(() => new Set<string>());
  const clients = await Promise.all(
    cases.map(async ([user, filter, , delivered], i) => {
      const c = await connect(user);
      c.on('message', (_t, p) => received[i]!.add(p.toString()));
      // mqtt.js rejects a SUBACK of 0x80 ("Subscribe error: Unspecified error").
      const granted = await c.subscribeAsync(filter, { qos: 1 }).then(
        (g) => g[0]!.qos !== 128,
        (err: Error) => (/Subscribe error/.test(err.message) ? false : Promise.reject(err)),
      );
      if (o.suback0x80) expect.soft(granted, `SUBACK for ${user} on ${filter}`).toBe(delivered);
      return c;
    }),
  );
  const writers = new Map<User, MqttClient>();
  for (const [, , probe] of cases) {
    const w = writerFor(probe);
    if (!writers.has(w)) writers.set(w, await connect(w));
  }
  await Promise.all(
    cases.map(([, , probe], i) =>
      writers.get(writerFor(probe))!.publishAsync(probe, `probe-${i}`, { qos: 1 }),
    ),
  );
  await new Promise((r) => setTimeout(r, 500));
  cases.forEach(([user, filter, probe, delivered], i) =>
    expect
      .soft(received[i]!.has(`probe-${i}`), `${user} subscribed to ${filter} gets ${probe}`)
      .toBe(delivered),
  );
  for (const c of [...clients, ...writers.values()]) await c.endAsync(true);
}

export async function checkPublishes(connect: Connect): Promise<void> {
  const readers = new Map<User, MqttClient>();
  const received = new Set<string>();
  for (const user of new Set(PUBLISH_CASES.map(([, t]) => readerFor(t)))) {
    const c = await connect(user);
    c.on('message', (_t, payload) => received.add(payload.toString()));
    const filters = PUBLISH_CASES.map(([, t]) => t).filter((t) => readerFor(t) === user);
    await c.subscribeAsync([...new Set(filters)], { qos: 1 });
    readers.set(user, c);
  }
  await Promise.all(
    PUBLISH_CASES.map(async ([user, topic], i) => {
      const c = await connect(user);
      c.on('error', () => {}); // Aedes closes a client whose publish it refuses
      await Promise.race([
        c.publishAsync(topic, `case-${i}`, { qos: 1 }).catch(() => {}),
        new Promise<void>((r) => c.once('close', () => r())),
      ]);
      c.end(true);
    }),
  );
  await new Promise((r) => setTimeout(r, 500));
  PUBLISH_CASES.forEach(([user, topic, allowed], i) =>
    expect.soft(received.has(`case-${i}`), `${user} publishing to ${topic}`).toBe(allowed),
  );
  for (const c of readers.values()) await c.endAsync(true);
}

/** A viewer's will on the operator topic is never published; an operator's is. */
export async function checkWills(connect: Connect): Promise<void> {
  const reader = await connect('viewer');
  const got: string[] = [];
  reader.on('message', (_t, p) => got.push(p.toString()));
  await reader.subscribeAsync('arm/arm1/operator', { qos: 1 });
  for (const user of ['viewer', 'operator'] as const) {
    const will = {
      topic: 'arm/arm1/operator',
      payload: Buffer.from(`will-${user}`),
      qos: 1 as const,
      retain: false,
    };
    const c = await connect(user, { will }).catch(() => null); // Mosquitto may refuse the viewer
    c?.stream.destroy(); // drop without DISCONNECT: the broker publishes the will
  }
  await new Promise((r) => setTimeout(r, 800));
  expect(got).toEqual(['will-operator']);
  await reader.endAsync(true);
}

export const readText = (file: string) => fs.readFileSync(file, 'utf8');
