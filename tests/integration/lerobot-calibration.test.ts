/**
 * LeRobot calibration in and out, with LeRobot's own code (lerobot 0.6.1 from PyPI, an SO-101
 * follower's `_save_calibration` / `_load_calibration`): LeRobot writes a calibration file,
 * `armtwin robot calibration import` puts it into a copy of the shipped so101 profile (polarity,
 * offset, limits, a backup of the old file), `… export` writes it back, and LeRobot reads back
 * exactly what it wrote.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import { MODELS_DIR } from '@armtwin/sim';
import { runLerobotScript } from '../helpers/lerobot-python.ts';
import { ARMTWIN } from './sim-helpers.ts';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-lerobot-cal-'));
const models = path.join(dir, 'models');
fs.cpSync(path.join(MODELS_DIR, 'so101'), path.join(models, 'so101'), { recursive: true });
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

/** An arm as LeRobot calibrates one, with a mirrored wrist and the extremes of each field. */
const CALIBRATION = {
  shoulder_pan: { id: 1, drive_mode: 0, homing_offset: -1470, range_min: 758, range_max: 3292 },
  shoulder_lift: { id: 2, drive_mode: 0, homing_offset: 2047, range_min: 0, range_max: 4095 },
  elbow_flex: { id: 3, drive_mode: 0, homing_offset: -2047, range_min: 889, range_max: 3096 },
  wrist_flex: { id: 4, drive_mode: 1, homing_offset: -1330, range_min: 857, range_max: 3290 },
  wrist_roll: { id: 5, drive_mode: 0, homing_offset: 0, range_min: 146, range_max: 147 },
  gripper: { id: 6, drive_mode: 0, homing_offset: 1407, range_min: 2031, range_max: 3476 },
};

const cli = (...args: string[]) =>
  execFileSync(process.execPath, [ARMTWIN, 'robot', 'calibration', ...args, '--models', models], {
    encoding: 'utf8',
    stdio: ['ignore', 'pipe', 'pipe'],
  });

describe('LeRobot calibration through armtwin', () => {
  const written = runLerobotScript<{ path: string }>('calibration_file.py', {
    op: 'write',
    dir: path.join(dir, 'lerobot'),
    id: 'my_follower',
    calibration: CALIBRATION,
  });

  test('import: each motor sets its servo; the old profile is kept as a backup', () => {
    const out = JSON.parse(cli('import', written.path, '--profile', 'so101')) as {
      backup: string;
    };
    const folder = path.join(models, 'so101');
    expect(fs.existsSync(path.join(folder, out.backup))).toBe(true);
    const parsed = parseProfile(
      JSON.parse(fs.readFileSync(path.join(folder, 'profile.json'), 'utf8')),
    );
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const by = (joint: string) => parsed.profile.servos.find((s) => s.joint === joint)!;
    // The middle of the range is the joint's zero; its ends are the limits.
    expect(by('shoulder_pan')).toMatchObject({
      polarity: 1,
      offset: 2.02,
      min: -111.35,
      max: 111.35,
    });
    expect(by('shoulder_lift')).toMatchObject({ polarity: 1, min: -179.96, max: 179.95 });
    expect(by('wrist_flex')).toMatchObject({ polarity: -1 });
  });

  test('export: LeRobot reads back exactly what it wrote', () => {
    const back = path.join(dir, 'exported', 'my_follower.json');
    fs.mkdirSync(path.dirname(back), { recursive: true });
    cli('export', '--profile', 'so101', '--out', back);
    expect(runLerobotScript('calibration_file.py', { op: 'read', path: back })).toEqual(
      CALIBRATION,
    );
    expect(fs.readFileSync(back, 'utf8').trim()).toBe(fs.readFileSync(written.path, 'utf8').trim());
  });

  test('a file naming a servo with another id is refused, the profile left as it was', () => {
    const bad = path.join(dir, 'bad.json');
    fs.writeFileSync(bad, JSON.stringify({ gripper: { ...CALIBRATION.gripper, id: 9 } }));
    const before = fs.readFileSync(path.join(models, 'so101', 'profile.json'), 'utf8');
    expect(() => cli('import', bad, '--profile', 'so101')).toThrow(/LeRobot's id 9/);
    expect(fs.readFileSync(path.join(models, 'so101', 'profile.json'), 'utf8')).toBe(before);
  });
});
