/**
 * One operator at a time (docs/protocol.md § Control), replayed on the embedded broker
 * (control-embedded.test.ts) and on Mosquitto running the generated configuration
 * (control-mosquitto.test.ts): a real `armtwin sim` logs in as its arm's device; alice, bob
 * (operators) and root (admin) are raw MQTT clients with their own credentials. What is checked
 * is the arm itself: the sim's reported positions, never just a refused publish.
 */
import fs from 'node:fs';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import { expect } from 'vitest';
import { hashPassword } from '@armtwin/auth';
import { parseAudit, parseHolder, type AuditEvent, type HolderRecord } from '@armtwin/protocol';
import { armtwin, StatusWatcher, type Child } from './sim-helpers.ts';

export const ARM = 'arm1';
export const CONTROL_USERS = ['alice', 'bob', 'root', 'arm1', 'watch'] as const;
export type ControlUser = (typeof CONTROL_USERS)[number];
export const controlPassword = (u: string) => `${u}-pw`;

/** A users file with two operators, an administrator, the arm's device and a viewer. */
export function writeControlUsers(
  dir: string,
  pw: (user: string) => string = controlPassword,
): string {
  const role = {
    alice: 'operator',
    bob: 'operator',
    root: 'admin',
    arm1: 'device',
    watch: 'viewer',
  };
  const users = CONTROL_USERS.map((name) => ({
    name,
    role: role[name],
    ...(name === 'arm1' ? { arm: 'arm1' } : {}),
    password: hashPassword(pw(name), { iterations: 1000 }),
  }));
  const file = path.join(dir, 'control-users.json');
  fs.writeFileSync(file, JSON.stringify({ users }, null, 2));
  return file;
}

/** The arm as a viewer sees it: status, the holder record and the audit events. */
export class ArmView {
  holder: HolderRecord | null = null;
  readonly audit: AuditEvent[] = [];
  /** Motion request feedback, JSON as received. */
  readonly feedback: { id?: string; status?: string; message?: string }[] = [];
  private constructor(readonly w: StatusWatcher) {}

  static async connect(url: string, user: string | null): Promise<ArmView> {
    const w = await StatusWatcher.connect(
      url,
      ARM,
      user ? { username: user, password: controlPassword(user) } : {},
    );
    const v = new ArmView(w);
    w.client.on('message', (topic, payload) => {
      if (topic === `arm/${ARM}/holder`) v.holder = parseHolder(payload);
      if (topic === `arm/${ARM}/feedback`) v.feedback.push(JSON.parse(payload.toString()));
      if (topic === `arm/${ARM}/audit`) {
        const e = parseAudit(payload);
        if (e) v.audit.push(e);
      }
    });
    await w.client.subscribeAsync(
      [`arm/${ARM}/holder`, `arm/${ARM}/audit`, `arm/${ARM}/feedback`],
      { qos: 1 },
    );
    return v;
  }

  heldBy(user: string | null, what = `holder ${user}`) {
    return this.w.until(() => (this.holder?.user === user ? this.holder : undefined), 15_000, what);
  }

  event(test: (e: AuditEvent) => boolean, what: string) {
    return this.w.until(() => this.audit.find(test), 15_000, what);
  }

  /** Waits until servo 0 reports `pwm` (±5), after item `from`. */
  reaches(pwm: number, from = 0) {
    return this.w.until(
      () => (this.w.positions(0, from).some(([, p]) => Math.abs(p - pwm) <= 5) ? true : undefined),
      15_000,
      `servo 0 at ${pwm}`,
    );
  }

  /** `n` more state samples after item `from` (the arm has had time to act on what came before). */
  async samples(n: number, from: number): Promise<number[]> {
    await this.w.until(
      () => (this.w.positions(0, from).length >= n ? true : undefined),
      15_000,
      `${n} state samples`,
    );
    return this.w.positions(0, from).map(([, p]) => p);
  }

  close() {
    return this.w.close();
  }
}

/** A user's own MQTT client, publishing on its per-user topics (or any topic, for forgeries). */
export async function asUser(url: string, user: ControlUser | null): Promise<MqttClient> {
  const c = await mqtt.connectAsync(url, {
    reconnectPeriod: 0,
    connectTimeout: 5000,
    ...(user ? { username: user, password: controlPassword(user) } : {}),
  });
  c.on('error', () => {}); // Aedes closes a client whose publish it refuses
  return c;
}

/** Publishes and does not wait for more than the broker's answer (a refusal may close it). */
export async function tryPublish(c: MqttClient, topic: string, payload: string): Promise<void> {
  await Promise.race([
    c.publishAsync(topic, payload, { qos: 1 }).catch(() => {}),
    new Promise<void>((r) => c.once('close', () => r())),
  ]);
}

export function startSim(url: string, credentials: boolean, leaseMs = 1000): Child {
  return armtwin([
    'sim',
    '--mqtt',
    url,
    '--arm',
    ARM,
    '--rate',
    '50',
    '--operator-lease',
    String(leaseMs),
    ...(credentials ? ['--username', 'arm1', '--password', controlPassword('arm1')] : []),
  ]);
}

const claim = (who: string) => `arm/${ARM}/claim/${who}`;
const control = (who: string) => `arm/${ARM}/control/${who}`;

/**
 * The whole story with the broker enforcing identity: alice takes arm1 and moves it; bob's
 * moves (his own topic, the plain topic, alice's topic) and forged claims never move it; bob
 * gets the arm when alice grants it, and again after alice holds it and drops (her lease
 * lapses); root takes it outright.
 */
export async function checkOneOperator(url: string): Promise<void> {
  const view = await ArmView.connect(url, 'watch');
  const alice = await asUser(url, 'alice');
  const bob = await asUser(url, 'bob');
  try {
    await view.heldBy(null, 'the sim announcing nobody holds arm1');

    await alice.publishAsync(claim('alice'), 'take', { qos: 1 });
    await view.heldBy('alice');
    await alice.publishAsync(control('alice'), '#000P1800T200!', { qos: 1 });
    await view.reaches(1800);

    // bob, on his own topic: refused by the arm, with a $ERR and an audit event.
    const before = view.w.items.length;
    await bob.publishAsync(control('bob'), '#000P1200T200!', { qos: 1 });
    const err = await view.w.frame(
      (f) => f.type === 'controllerError' && f.text.includes('controlled by alice'),
      before,
    );
    expect(err.frame).toMatchObject({ type: 'controllerError' });
    await view.event((e) => e.kind === 'refused-command' && e.by === 'bob', 'bob refused');
    // ...and around the broker: the plain topic and alice's topic are not bob's to write.
    for (const topic of [`arm/${ARM}/control`, control('alice')]) {
      const forger = await asUser(url, 'bob');
      await tryPublish(forger, topic, '#000P1200T200!');
      forger.end(true);
    }
    // A forged grant, on bob's own claim topic and on alice's.
    await bob.publishAsync(claim('bob'), 'grant bob', { qos: 1 });
    await view.event(
      (e) => e.kind === 'refused-claim' && e.by === 'bob' && e.detail.includes('only alice'),
      'the forged grant refused',
    );
    const forger = await asUser(url, 'bob');
    await tryPublish(forger, claim('alice'), 'grant bob');
    forger.end(true);
    // A motion request that would execute, on the plain request topic and on bob's own.
    for (const [id, topic] of [
      ['bob-plain', `arm/${ARM}/request`],
      ['bob-own', `arm/${ARM}/request/bob`],
    ] as const) {
      const req = { id, mode: 'joint', targets: [{ servos: { '000': 1200 } }], execute: true };
      await bob.publishAsync(topic, JSON.stringify(req), { qos: 1 });
      const f = await view.w.until(() => view.feedback.find((x) => x.id === id), 15_000, id);
      expect(f).toMatchObject({ status: 'failed', message: 'not executed: controlled by alice' });
    }
    // The arm never moved: every sample after all that still says 1800.
    const after = await view.samples(25, before);
    expect(after.every((p) => Math.abs(p - 1800) <= 5)).toBe(true);
    expect(view.holder?.user).toBe('alice');

    // bob asks, alice grants: bob moves the arm.
    await bob.publishAsync(claim('bob'), 'ask', { qos: 1 });
    await view.w.until(() => (view.holder?.requests.includes('bob') ? true : undefined));
    await alice.publishAsync(claim('alice'), 'grant bob', { qos: 1 });
    await view.heldBy('bob');
    const granted = view.w.items.length;
    await bob.publishAsync(control('bob'), '#000P1200T200!', { qos: 1 });
    await view.reaches(1200, granted);
    // ...and alice's moves are now the refused ones.
    await alice.publishAsync(control('alice'), '#000P2000T200!', { qos: 1 });
    await view.event((e) => e.kind === 'refused-command' && e.by === 'alice', 'alice refused');

    // bob releases; alice holds, beats, and drops mid-way: her lease lapses and bob gets it.
    await bob.publishAsync(claim('bob'), 'release', { qos: 1 });
    await view.heldBy(null);
    await alice.publishAsync(claim('alice'), 'take', { qos: 1 });
    await view.heldBy('alice');
    // alice's page beats, as the HUD does (every 500 ms; faster here).
    const beating = setInterval(() => alice.publish(claim('alice'), 'beat', { qos: 1 }), 200);
    await bob.publishAsync(claim('bob'), 'take', { qos: 1 }); // refused: alice holds it
    await view.event(
      (e) => e.kind === 'refused-claim' && e.by === 'bob' && e.detail.includes('alice'),
      'take refused while alice holds',
    );
    // A slow move, and alice vanishes mid-way: no release, no more beats.
    const slow = view.w.items.length;
    await alice.publishAsync(control('alice'), '#000P2000T6000!', { qos: 1 });
    await view.w.until(
      () => (view.w.positions(0, slow).some(([, p]) => p > 1300) ? true : undefined),
      15_000,
      'the slow move under way',
    );
    clearInterval(beating);
    alice.stream.destroy();
    await view.event((e) => e.kind === 'lost' && e.by === 'alice', 'alice lost control');
    await view.heldBy(null);
    // The arm stopped where it was, far from 2000, and stays there.
    const lost = view.w.items.length;
    await view.samples(5, lost);
    const still = (await view.samples(25, view.w.items.length)).slice(-20);
    expect(Math.max(...still) - Math.min(...still)).toBeLessThanOrEqual(1);
    expect(still.at(-1)!).toBeLessThan(1900);
    await bob.publishAsync(claim('bob'), 'take', { qos: 1 });
    await view.heldBy('bob');
    const retaken = view.w.items.length;
    await bob.publishAsync(control('bob'), '#000P1600T200!', { qos: 1 });
    await view.reaches(1600, retaken);

    // An administrator takes the arm outright; an operator cannot (its override is denied).
    const root = await asUser(url, 'root');
    await root.publishAsync(`arm/${ARM}/override/root`, 'take', { qos: 1 });
    const h = await view.heldBy('root');
    expect(h.role).toBe('admin');
    await view.event((e) => e.kind === 'admin-take-over' && e.by === 'root', 'admin take-over');
    const op = await asUser(url, 'bob');
    await tryPublish(op, `arm/${ARM}/override/bob`, 'take');
    op.end(true);
    await view.samples(10, view.w.items.length);
    expect(view.holder?.user).toBe('root');
    await root.publishAsync(claim('root'), 'release', { qos: 1 });
    await view.heldBy(null);
    await root.endAsync(true);
  } finally {
    alice.end(true);
    bob.end(true);
    await view.close();
  }
}
