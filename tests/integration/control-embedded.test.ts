/**
 * One operator at a time on the embedded broker (`armtwin broker` / `npm start`): with a users
 * file the broker vouches for each name (control-cases.ts); without one (the anonymous local
 * demo) the plain control topic moves the arm as before, and a self-declared holder is kept.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { startBroker, type Broker } from '@armtwin/broker';
import { loadUsers } from '@armtwin/auth';
import type { Child } from './sim-helpers.ts';
import {
  ArmView,
  ARM,
  asUser,
  checkOneOperator,
  startSim,
  writeControlUsers,
} from './control-cases.ts';

let dir = '';
let secure: Broker;
let demo: Broker;
const sims: Child[] = [];

beforeAll(async () => {
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-control-'));
  secure = await startBroker({ port: 0, users: loadUsers(writeControlUsers(dir)) });
  demo = await startBroker({ port: 0 });
});

afterAll(async () => {
  for (const s of sims) await s.stop();
  await secure?.close();
  await demo?.close();
  fs.rmSync(dir, { recursive: true, force: true });
});

describe('one operator at a time on the embedded broker', () => {
  test("with a users file: bob's moves never reach the arm alice holds; grant, lapse, admin", async () => {
    const url = `mqtt://127.0.0.1:${secure.port}`;
    sims.push(startSim(url, true));
    await checkOneOperator(url);
  });

  test('anonymous demo: the plain topic moves the arm until someone takes control', async () => {
    const url = `mqtt://127.0.0.1:${demo.port}`;
    sims.push(startSim(url, false));
    const view = await ArmView.connect(url, null);
    const anyone = await asUser(url, null);
    try {
      await view.heldBy(null, 'the sim announcing nobody holds arm1');
      await anyone.publishAsync(`arm/${ARM}/control`, '#000P1700T200!', { qos: 1 });
      await view.reaches(1700);
      // A page takes control under a self-declared name: the plain topic's moves are refused,
      // its stops still pass.
      await anyone.publishAsync(`arm/${ARM}/claim/guest-1`, 'take', { qos: 1 });
      await view.heldBy('guest-1');
      const from = view.w.items.length;
      await anyone.publishAsync(`arm/${ARM}/control`, '#000P1300T200!', { qos: 1 });
      await view.event((e) => e.kind === 'refused-command' && e.by === '', 'plain move refused');
      const after = await view.samples(20, from);
      expect(after.every((p) => Math.abs(p - 1700) <= 5)).toBe(true);
      await anyone.publishAsync(`arm/${ARM}/claim/guest-1`, 'release', { qos: 1 });
      await view.heldBy(null);
      const freed = view.w.items.length;
      await anyone.publishAsync(`arm/${ARM}/control`, '#000P1300T200!', { qos: 1 });
      await view.reaches(1300, freed);
    } finally {
      await anyone.endAsync(true);
      await view.close();
    }
  });
});
