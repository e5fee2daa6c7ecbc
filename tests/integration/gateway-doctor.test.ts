/**
 * The servo doctor end to end: `armtwin sim --bus feetech` plays the shipped SO-101 on one side
 * of a socat pty pair with faults of the bench injected (`--bus-fault`, `--overheat`), and
 * `armtwin gateway --bus feetech --doctor` on the other side reports each as a finding with
 * its fix, exiting 1; a healthy arm gets "no problem found" and 0. A gateway started normally
 * logs the same findings before it runs. (A wrong baud rate is proved on the emulated bus in
 * packages/servo-bus/test/doctor.test.ts: a pty carries no baud rate to the simulator.)
 */
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { useMosquitto } from '../helpers/use-services.ts';
import { ARMTWIN, armtwin, StatusWatcher } from './sim-helpers.ts';
import { serialLine } from './serial-line.ts';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-doctor-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));
const broker = useMosquitto();

let n = 0;
/** A simulated SO-101 on a fresh pty pair with `faults` (sim arguments); its host side. */
function so101Line(faults: string[]) {
  const k = ++n;
  const host = path.join(dir, `host${k}`);
  const line = serialLine(
    host,
    path.join(dir, `arm${k}`),
    (arm) => [
      'sim',
      '--bus',
      'feetech',
      '--serial',
      arm,
      '--baud',
      '1000000',
      '--profile',
      'so101',
      ...faults,
    ],
    'simulated servo bus on the serial line',
  );
  return { host, line };
}

/** Runs the doctor against a simulated SO-101 with `faults`. */
async function doctor(faults: string[]): Promise<{ code: number | null; out: string }> {
  const { host, line } = so101Line(faults);
  await line.start();
  try {
    const r = spawnSync(
      process.execPath,
      [ARMTWIN, 'gateway', '--bus', 'feetech', '--serial', host, '--profile', 'so101', '--doctor'],
      { encoding: 'utf8', timeout: 60_000 },
    );
    return { code: r.status, out: r.stdout + r.stderr };
  } finally {
    await line.stop();
  }
}

describe('armtwin gateway --bus feetech --doctor', () => {
  test('a healthy SO-101: every servo described, no problem, exit 0', async () => {
    const r = await doctor([]);
    expect(r.out).toMatch(/1000000 baud: servos 1, 2, 3, 4, 5, 6/);
    expect(r.out).toMatch(/servo 6: model 777, firmware 3\.10, 7\.4 V/);
    expect(r.out).toMatch(/no problem found/);
    expect(r.code).toBe(0);
  });

  test('a clash, a missing and an extra servo, firmware, overheat and overload: each found', async () => {
    const r = await doctor([
      ...[
        'clash:3',
        'absent:4',
        'extra:9',
        'field:2:firmwareMinorVersion=9',
        'field:6:status=32',
      ].flatMap((f) => ['--bus-fault', f]),
      '--overheat',
      '5:80',
    ]);
    expect(r.code).toBe(1);
    for (const kind of ['garbled', 'missing', 'extra', 'firmware', 'overheat', 'overload'])
      expect(r.out, kind).toMatch(new RegExp(`\\[${kind}\\] .*\\n  fix: `));
    expect(r.out).toMatch(/\[garbled\] id 3 answered with a garbled packet/);
    expect(r.out).toMatch(/\[missing\] servos 4 of the profile/);
    expect(r.out).toMatch(/give them the profile's missing ids \(4\)/);
  });

  test('7.4 V servos on a 12 V supply: the voltage variant, and switch it off', async () => {
    const r = await doctor(
      [1, 2, 3, 4, 5, 6].flatMap((id) => [
        '--bus-fault',
        `field:${id}:maxVoltageLimit=80`,
        '--bus-fault',
        `field:${id}:presentVoltage=121`,
      ]),
    );
    expect(r.code).toBe(1);
    expect(r.out).toMatch(/\[voltage-variant\] servos 1, 2, 3, 4, 5, 6 measure 12\.1 V/);
    expect(r.out).toMatch(/fix: switch the supply off now/);
  });

  test('a gateway started on a faulty bus logs the findings, then runs', async () => {
    const { host, line } = so101Line(['--bus-fault', 'absent:4']);
    await line.start();
    const gw = armtwin([
      'gateway',
      '--bus',
      'feetech',
      '--serial',
      host,
      '--profile',
      'so101',
      '--mqtt',
      broker().url,
      '--arm',
      'doc1',
    ]);
    const w = await StatusWatcher.connect(broker().url, 'doc1');
    try {
      // The gateway runs: positions of the servos that answered come through.
      await w.until(() => (w.angleSamples(1).length ? true : undefined), 120_000, 'positions');
      expect(gw.output()).toMatch(
        /servo doctor: \[missing\] servos 4 of the profile did not answer/,
      );
    } finally {
      await w.close();
      await gw.stop();
      await line.stop();
    }
  });
});
