/**
 * The emulated servo buses of `@armtwin/servo-bus`, proved with the vendors' own SDKs, which
 * nobody here wrote: a socat pty pair is the serial line, `tests/helpers/serve-servo-bus.ts`
 * serves the emulated bus on one end, and Python scripts on the other drive it with ROBOTIS's
 * `dynamixel-sdk` and Feetech's `feetech-servo-sdk` (ping, present position, temperature and
 * voltage, torque, a goal watched until reached, GroupSyncWrite/GroupSyncRead, the status error
 * byte). The SDKs live in the venv `scripts/install-deps.sh` makes; without it this test fails.
 */
import { execFile, spawn, type ChildProcess } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import type { EmulatedServoSpec } from '@armtwin/servo-bus';
import { REPO_ROOT } from '../helpers/files.ts';
import { servoSdkPython } from '../helpers/servo-sdk-python.ts';

const run = promisify(execFile);
const HELPERS = path.join(REPO_ROOT, 'tests', 'helpers');

interface Case {
  protocol: 'dynamixel' | 'feetech';
  script: string;
  baud: number;
  servos: EmulatedServoSpec[];
}

const CASES: Case[] = [
  {
    protocol: 'dynamixel',
    script: 'dynamixel_check.py',
    baud: 57_600, // the X-series' factory baud rate
    servos: [
      { id: 1, model: 'XM430-W350', temperatureC: 36, voltageV: 12.2 },
      { id: 2, model: 'XL430-W250', position: 1500, temperatureC: 41, voltageV: 11.1 },
    ],
  },
  {
    protocol: 'feetech',
    script: 'feetech_check.py',
    baud: 1_000_000, // the STS3215's factory baud rate
    servos: [
      { id: 1, model: 'STS3215', temperatureC: 33, voltageV: 7.4 },
      { id: 2, model: 'STS3215', position: 1500, temperatureC: 35, voltageV: 7.2 },
    ],
  },
];

async function until(what: string, ok: () => boolean, timeoutMs: number): Promise<void> {
  const deadline = Date.now() + timeoutMs;
  while (!ok()) {
    if (Date.now() > deadline) throw new Error(`${what} after ${timeoutMs} ms`);
    await new Promise((r) => setTimeout(r, 50));
  }
}

async function stop(child: ChildProcess | undefined): Promise<void> {
  if (!child || child.exitCode !== null || child.signalCode !== null) return;
  const gone = new Promise((r) => child.once('exit', r));
  child.kill('SIGTERM');
  const timer = setTimeout(() => child.kill('SIGKILL'), 5000);
  await gone;
  clearTimeout(timer);
}

let python: string;
beforeAll(() => {
  python = servoSdkPython();
});

describe.each(CASES)(
  '$protocol: the vendor SDK against the emulated bus',
  ({ protocol, script, baud, servos }) => {
    let dir = '';
    let socat: ChildProcess | undefined;
    let serve: ChildProcess | undefined;
    let serveLog = '';
    let result: Record<string, unknown>;

    beforeAll(async () => {
      dir = fs.mkdtempSync(path.join(os.tmpdir(), `armtwin-servo-${protocol}-`));
      const hostSide = path.join(dir, 'host');
      const busSide = path.join(dir, 'bus');
      socat = spawn(
        'socat',
        ['-d', '-d', `pty,raw,echo=0,link=${hostSide}`, `pty,raw,echo=0,link=${busSide}`],
        { stdio: 'ignore' },
      );
      await until(
        'socat made no pty pair',
        () => fs.existsSync(hostSide) && fs.existsSync(busSide),
        5000,
      );
      serve = spawn(
        process.execPath,
        [
          '--import',
          'tsx',
          path.join(HELPERS, 'serve-servo-bus.ts'),
          '--protocol',
          protocol,
          '--port',
          busSide,
          '--baud',
          String(baud),
          '--servos',
          JSON.stringify(servos),
        ],
        { cwd: REPO_ROOT, stdio: ['ignore', 'pipe', 'pipe'] },
      );
      serve.stdout!.on('data', (d: Buffer) => (serveLog += d.toString()));
      serve.stderr!.on('data', (d: Buffer) => (serveLog += d.toString()));
      await until(
        `the emulated bus did not start:\n${serveLog}`,
        () => serveLog.includes('servo bus ready'),
        20_000,
      );
      try {
        const { stdout } = await run(
          python,
          [path.join(HELPERS, 'servo-sdk', script), hostSide, String(baud)],
          { timeout: 90_000 },
        );
        result = JSON.parse(stdout.trim().split('\n').at(-1)!) as Record<string, unknown>;
      } catch (err) {
        const e = err as { stdout?: string; stderr?: string; message: string };
        throw new Error(
          `${script} failed: ${e.message}\n${e.stdout ?? ''}${e.stderr ?? ''}\nbus log:\n${serveLog}`,
          { cause: err },
        );
      }
      console.log(`${script}: ${JSON.stringify(result)}`);
    });

    afterAll(async () => {
      await stop(serve);
      await stop(socat);
      if (dir) fs.rmSync(dir, { recursive: true, force: true });
    });

    test('PING finds both servos with their model numbers, and nothing at id 3', () => {
      const models = protocol === 'dynamixel' ? [1020, 1060] : [777, 777];
      expect(result.ping).toEqual({
        '1': { model: models[0], error: 0 },
        '2': { model: models[1], error: 0 },
      });
      expect(result.ping_absent).toBe('[TxRxResult] There is no status packet!');
      if (protocol === 'dynamixel') expect(result.broadcast_ping).toEqual({ '1': 1020, '2': 1060 });
    });

    test('present position, temperature and voltage read as the bus was set up', () => {
      const extra = protocol === 'feetech' ? { error: 0 } : {};
      expect(result.present).toEqual({
        '1': {
          position: servos[0]!.position ?? 2048,
          temperature: servos[0]!.temperatureC,
          voltage: servos[0]!.voltageV,
          ...extra,
        },
        '2': {
          position: servos[1]!.position,
          temperature: servos[1]!.temperatureC,
          voltage: servos[1]!.voltageV,
          ...extra,
        },
      });
    });

    test('torque goes on and off', () => {
      expect(result.torque_on).toEqual([1, 1]);
      expect(result.torque_off).toEqual([0, 0]);
    });

    test('a goal written at a speed is reached, the position passing through on the way', () => {
      const goal = result.goal as { seconds: number; final: number; in_between: number };
      expect(goal.final).toBe(3072);
      // 1024 ticks at 50 × 0.229 rev/min (Dynamixel, 1.3 s) or 400 steps/s (Feetech, 2.6 s): slow
      // enough that the SDK's polls see it on the way even on a loaded machine. No time is
      // asserted: the positions in between show it moved at a speed rather than jumped.
      expect(goal.in_between).toBeGreaterThan(0);
    });

    test('GroupSyncWrite moves both servos, GroupSyncRead watches them get there', () => {
      expect(result.sync_write).toBe('[TxRxResult] Communication success!');
      expect((result.sync as { final: unknown }).final).toEqual({ '1': 1024, '2': 2500 });
      if (protocol === 'feetech')
        expect((result.sync as { negative_speed_seen: boolean }).negative_speed_seen).toBe(true);
    });

    test(
      protocol === 'dynamixel'
        ? 'a goal past the limit comes back with the Data Limit error'
        : 'a negative multi-turn goal in the sign-bit encoding is reached',
      () => {
        if (protocol === 'dynamixel')
          expect(result.limit_error).toEqual({
            error: 6,
            text: '[RxPacketError] The data value exceeds the limit value!',
          });
        else expect(result.negative).toMatchObject({ polls: expect.any(Number) });
      },
    );
  },
);
