/**
 * The simulator's servo buses (`armtwin sim --bus dynamixel|feetech --serial PATH`), proved with
 * the vendors' own SDKs, which nobody here wrote: a socat pty pair is the serial line, the sim
 * answers on one end as a bus of its profile's servos, and Python scripts on the other drive it
 * with ROBOTIS's `dynamixel-sdk` and Feetech's `feetech-servo-sdk` (ping, present position,
 * temperature and voltage, torque, a goal watched until reached, GroupSyncWrite/GroupSyncRead,
 * the status error byte). The profile (two servos, ids 001 and 002, on a two-joint URDF) is
 * written to a temporary models folder; the sim's fault flags set what the sensors read. The
 * SDKs live in the venv `scripts/install-deps.sh` makes; without it this test fails.
 */
import { execFile } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { promisify } from 'node:util';
import { afterAll, beforeAll, describe, expect, test } from 'vitest';
import { REPO_ROOT } from '../helpers/files.ts';
import { servoSdkPython } from '../helpers/servo-sdk-python.ts';
import { serialLine } from './serial-line.ts';

const run = promisify(execFile);
const SDK_CHECKS = path.join(REPO_ROOT, 'tests', 'helpers', 'servo-sdk');
const PROFILE = 'sdk2';
/** Servo 002's home angle: 2048 − 45° × 4096/360 = tick 1536. */
const HOME_002_DEG = -45;

const URDF = `<?xml version="1.0"?>
<robot name="${PROFILE}">
  <link name="base"/>
  <link name="upper"/>
  <link name="tip"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-3.1" upper="3.1" effort="1" velocity="3"/>
  </joint>
  <joint name="j2" type="revolute">
    <parent link="upper"/><child link="tip"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>
    <limit lower="-3.1" upper="3.1" effort="1" velocity="3"/>
  </joint>
</robot>
`;

const servo = (id: string, joint: string) => ({
  id,
  name: joint,
  joint,
  type: 'revolute',
  units: 'angle',
  min: -175,
  max: 175,
  maxSpeed: 180,
});

const PROFILE_JSON = {
  format: 'armtwin-profile/1',
  name: PROFILE,
  title: 'Two bus servos for the vendor SDK checks',
  urdf: `${PROFILE}.urdf`,
  ik: { kind: 'numeric', baseLink: 'base', tipLink: 'tip' },
  servos: [servo('001', 'j1'), servo('002', 'j2')],
  poses: { home: { unit: 'servo', servos: { '001': 0, '002': HOME_002_DEG } } },
};

interface Case {
  protocol: 'dynamixel' | 'feetech';
  script: string;
  baud: number;
  /** The sim's fault flags: what the sensors read. */
  faults: string[];
  /** Model number PING answers (the emulator's default model of each protocol). */
  model: number;
  present: Record<'1' | '2', { temperature: number; voltage: number }>;
}

const CASES: Case[] = [
  {
    protocol: 'dynamixel',
    script: 'dynamixel_check.py',
    baud: 57_600, // the X-series' factory baud rate
    faults: ['--overheat', '2:41'],
    model: 1020, // XM430-W350
    present: { '1': { temperature: 25, voltage: 12 }, '2': { temperature: 41, voltage: 12 } },
  },
  {
    protocol: 'feetech',
    script: 'feetech_check.py',
    baud: 1_000_000, // the STS3215's factory baud rate
    faults: ['--overheat', '2:35', '--undervolt', '7200'],
    model: 777, // STS3215
    present: { '1': { temperature: 25, voltage: 7.2 }, '2': { temperature: 35, voltage: 7.2 } },
  },
];

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-servo-sdk-'));
const MODELS = path.join(dir, 'models');
let python: string;

beforeAll(() => {
  python = servoSdkPython();
  fs.mkdirSync(path.join(MODELS, PROFILE), { recursive: true });
  fs.writeFileSync(path.join(MODELS, PROFILE, `${PROFILE}.urdf`), URDF);
  fs.writeFileSync(path.join(MODELS, PROFILE, 'profile.json'), JSON.stringify(PROFILE_JSON));
});

afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

describe.each(CASES)(
  '$protocol: the vendor SDK against `armtwin sim --bus $protocol`',
  ({ protocol, script, baud, faults, model, present }) => {
    const hostSide = path.join(dir, `${protocol}-host`);
    const line = serialLine(
      hostSide,
      path.join(dir, `${protocol}-bus`),
      (busSide) => [
        'sim',
        '--bus',
        protocol,
        '--serial',
        busSide,
        '--baud',
        String(baud),
        '--profile',
        PROFILE,
        '--models',
        MODELS,
        ...faults,
      ],
      'simulated servo bus on the serial line',
    );
    let result: Record<string, unknown>;

    beforeAll(async () => {
      await line.start();
      try {
        const { stdout } = await run(
          python,
          [path.join(SDK_CHECKS, script), hostSide, String(baud)],
          { timeout: 90_000 },
        );
        result = JSON.parse(stdout.trim().split('\n').at(-1)!) as Record<string, unknown>;
      } catch (err) {
        const e = err as { stdout?: string; stderr?: string; message: string };
        throw new Error(`${script} failed: ${e.message}\n${e.stdout ?? ''}${e.stderr ?? ''}`, {
          cause: err,
        });
      }
      console.log(`${script}: ${JSON.stringify(result)}`);
    });

    afterAll(() => line.stop());

    test('PING finds both servos with their model numbers, and nothing at id 3', () => {
      expect(result.ping).toEqual({
        '1': { model, error: 0 },
        '2': { model, error: 0 },
      });
      expect(result.ping_absent).toBe('[TxRxResult] There is no status packet!');
      if (protocol === 'dynamixel')
        expect(result.broadcast_ping).toEqual({ '1': model, '2': model });
    });

    test("present position, temperature and voltage: the profile's home pose and the sim's sensors", () => {
      const extra = protocol === 'feetech' ? { error: 0 } : {};
      expect(result.present).toEqual({
        '1': { position: 2048, ...present['1'], ...extra },
        '2': { position: 2048 + (HOME_002_DEG * 4096) / 360, ...present['2'], ...extra },
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
