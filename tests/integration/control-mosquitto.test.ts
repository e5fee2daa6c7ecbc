/**
 * One operator at a time on Mosquitto 2.0: `armtwin deploy-mosquitto` writes the ACL from the
 * role table, each operator's control and claim topics ending in their own name
 * (`topic write arm/+/control/alice`), so identity reaches the controller through the broker;
 * the same story as on the embedded broker (control-cases.ts).
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { startService, type ServiceProcess } from '../helpers/process.ts';
import { deployedMosquittoSpec, REPO_ROOT } from '../helpers/services.ts';
import { ARMTWIN, type Child } from './sim-helpers.ts';
import { checkOneOperator, startSim, writeControlUsers } from './control-cases.ts';

let svc: ServiceProcess;
let port = 0;
let acl = '';
let sim: Child | undefined;

beforeAll(async () => {
  svc = await startService('mosquitto-control', 1, (dir, p) => {
    port = p[0]!;
    execFileSync(
      process.execPath,
      [
        ARMTWIN,
        'deploy-mosquitto',
        '--users',
        writeControlUsers(dir),
        '--out',
        dir,
        '--persistence-dir',
        `${dir}/`,
        '--port',
        String(port),
        '--mqtts-port',
        '0',
        '--wss-port',
        '0',
        '--bind',
        '127.0.0.1',
      ],
      { cwd: REPO_ROOT, stdio: 'pipe' },
    );
    acl = fs.readFileSync(path.join(dir, 'acl'), 'utf8');
    return deployedMosquittoSpec(dir, p);
  });
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
