/**
 * `armtwin robot calibration import|export`: a LeRobot calibration file (per arm, written by
 * `lerobot-calibrate`) into a profile's bus calibration, and back. The mapping is
 * `@armtwin/servo-bus`'s (lerobot-calibration.ts); the profile is written as the HUD's wizard
 * writes it (`applyCalibration`, a dated backup, atomic rename), so a bus gateway running it
 * takes the calibration at once.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Command } from 'commander';
import { applyCalibration, parseProfile } from '@armtwin/robot';
import {
  lerobotCalibrationOf,
  matchLerobotCalibration,
  parseLerobotCalibration,
  type LerobotKept,
} from '@armtwin/servo-bus';
import { MODELS_DIR } from '@armtwin/sim';
import { replaceProfileFile } from '@armtwin/http-api';

interface Flags {
  profile: string;
  models: string;
  out?: string;
}

/** The key under which a profile keeps what LeRobot's file needs back (ignored by the parser). */
export const LEROBOT_KEY = '$lerobot';

function readJson(file: string, what: string): unknown {
  let text: string;
  try {
    text = fs.readFileSync(file, 'utf8');
  } catch (err) {
    throw new Error(`cannot read ${what} ${file}: ${(err as Error).message}`, { cause: err });
  }
  try {
    return JSON.parse(text) as unknown;
  } catch (err) {
    throw new Error(`${what} ${file} is not JSON: ${(err as Error).message}`, { cause: err });
  }
}

function loadProfile(flags: Flags) {
  const file = path.join(flags.models, flags.profile, 'profile.json');
  const raw = readJson(file, 'profile') as Record<string, unknown>;
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(`profile ${file}:\n  ${parsed.errors.join('\n  ')}`);
  return { file, raw, profile: parsed.profile };
}

export function importLerobotCalibration(source: string, flags: Flags): Record<string, unknown> {
  const read = parseLerobotCalibration(readJson(source, 'LeRobot calibration'));
  if (!read.ok) throw new Error(`LeRobot calibration ${source}:\n  ${read.errors.join('\n  ')}`);
  const { file, raw, profile } = loadProfile(flags);
  const matched = matchLerobotCalibration(read.calibration, profile.servos);
  if (!matched.ok)
    throw new Error(`cannot calibrate ${profile.name}:\n  ${matched.errors.join('\n  ')}`);
  const applied = applyCalibration(raw, matched.servos);
  if (!applied.ok)
    throw new Error(`cannot calibrate ${profile.name}:\n  ${applied.errors.join('\n  ')}`);
  const next = { ...applied.raw, [LEROBOT_KEY]: matched.kept };
  const backup = replaceProfileFile(file, next);
  return { profile: profile.name, file, backup, servos: matched.servos };
}

export function exportLerobotCalibration(flags: Flags): string {
  const { raw, profile } = loadProfile(flags);
  const kept = raw[LEROBOT_KEY] as LerobotKept | undefined;
  const servos = profile.servos.filter((s) => s.units === 'angle' && s.type === 'revolute');
  if (!servos.length) throw new Error(`profile ${profile.name} has no bus servos (units "angle")`);
  return `${JSON.stringify(lerobotCalibrationOf(servos, kept), null, 4)}\n`;
}

export function registerRobotCalibration(robot: Command): void {
  const calibration = robot
    .command('calibration')
    .description("a LeRobot calibration file into a profile's bus calibration, and back");
  calibration
    .command('import')
    .description(
      "a LeRobot calibration .json (lerobot-calibrate's) → the profile's polarity, offset, limits",
    )
    .argument(
      '<file>',
      'the calibration file, e.g. ~/.cache/huggingface/lerobot/calibration/robots/so101_follower/my_arm.json',
    )
    .requiredOption('--profile <name>', 'the profile to calibrate')
    .option('--models <dir>', 'the folder of robot profiles', MODELS_DIR)
    .addHelpText(
      'after',
      `
Each motor goes to the profile servo of the same name (joint or name), else the same id; the ids
must agree. drive_mode 1 is polarity -1; the middle of range_min..range_max is the joint's zero
(LeRobot's degrees); the range's ends are the limits. The homing offset stays in the servo and
is kept in the profile ("$lerobot") for export. The old profile is kept as profile.json.<time>.bak.`,
    )
    .action((file: string, flags: Flags) => {
      process.stdout.write(`${JSON.stringify(importLerobotCalibration(file, flags))}\n`);
    });
  calibration
    .command('export')
    .description("the profile's bus calibration as a LeRobot calibration .json")
    .requiredOption('--profile <name>', 'the profile to export')
    .option('--models <dir>', 'the folder of robot profiles', MODELS_DIR)
    .option('--out <file>', 'write it there (default: standard output)')
    .action((flags: Flags) => {
      const text = exportLerobotCalibration(flags);
      if (flags.out) fs.writeFileSync(flags.out, text);
      else process.stdout.write(text);
    });
}
