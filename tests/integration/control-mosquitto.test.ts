/**
 * One operator at a time on Mosquitto 2.0: `armtwin deploy-mosquitto` writes the ACL from the
 * role table, each operator's control and claim topics ending in their own name
 * (`topic write arm/+/control/alice`), so identity reaches the controller through the broker;
 * the same story as on the embedded broker (control-cases.ts).
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import type { ServiceProcess } from '../helpers/process.ts';
import { startDeployedMosquitto } from '../helpers/mosquitto.ts';
import type { Child } from './sim-helpers.ts';
import { checkOneOperator, startSim, writeControlUsers } from './control-cases.ts';

let svc: ServiceProcess;
let port = 0;
let acl = '';
let sim: Child | undefined;

beforeAll(async () => {
  svc = await startDeployedMosquitto('mosquitto-control', (dir) => writeControlUsers(dir));
  port = svc.spec.ports[0]!;
  acl = fs.readFileSync(path.join(svc.spec.dir, 'acl'), 'utf8');
});

afterAll(async () => {
  await sim?.stop();
  await svc?.dispose({ keepLogs: false });
});

describe('one operator at a time on Mosquitto (generated acl)', () => {
  test('the acl gives each operator its own control and claim topics, not the plain one', () => {
    expect(acl).toContain('user alice\n');
    expect(acl).toContain('topic write arm/+/control/alice\n');
    expect(acl).toContain('topic write arm/+/claim/alice\n');
    expect(acl).not.toMatch(/topic (read)?write arm\/\+\/control\n/);
    expect(acl).toContain('topic write arm/+/override/root\n');
    expect(acl).not.toContain('arm/+/override/alice');
  });

  test("bob's moves never reach the arm alice holds; grant, lapse, admin", async () => {
    const url = `mqtt://127.0.0.1:${port}`;
    sim = startSim(url, true);
    await checkOneOperator(url);
  });
});
