/**
 * Recordings out of armtwin: an arm's stored history over a time range, read from InfluxDB, as
 * MCAP (Foxglove, Lichtblick) or CSV. Used by `armtwin export` and the history API's download.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Writable } from 'node:stream';
import { parseUrdfJoints } from '@armtwin/robot';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import {
  announcedProfile,
  storedProfile,
  type BrokerLogin,
  type FoundProfile,
  type ProfileSource,
} from './arm-profile.ts';
import { csvLines } from './csv.ts';
import { streamWritable, writeMcap, type McapCounts, type RecordingRobot } from './mcap.ts';
import type { HistoryReader } from '../history/reader.ts';
import { readRecording } from './read-recording.ts';
import { selfContainedUrdf } from './robot-description.ts';

export { readRecording } from './read-recording.ts';
export { writeMcap, streamWritable, type RecordingRobot, type McapCounts } from './mcap.ts';
export { csvLines, CSV_HEADER } from './csv.ts';
export { FOXGLOVE_TOPICS } from './topics.ts';
export { selfContainedUrdf, meshMediaType, type RobotDescription } from './robot-description.ts';
export {
  storedProfile,
  announcedProfile,
  type BrokerLogin,
  type FoundProfile,
  type ProfileSource,
} from './arm-profile.ts';
export type { Recording } from './recording.ts';

export const EXPORT_FORMATS = ['mcap', 'csv'] as const;
export type ExportFormat = (typeof EXPORT_FORMATS)[number];

/**
 * A mesh of robot folder `dir` by the name its URDF (at `urdfFile`) gives it, as the HUD finds
 * it: `package://<pkg>/<path>` is `<path>` in the folder (the folder stands for every package),
 * anything else is relative to the URDF. Never outside the folder.
 */
function readFolderMesh(dir: string, urdfFile: string, filename: string): Uint8Array {
  const pkg = /^package:\/\/[^/]+\/(.+)$/.exec(filename);
  if (!pkg && /^[a-z][a-z0-9+.-]*:/i.test(filename))
    throw new Error('not a file of the robot folder');
  const file = pkg ? path.join(dir, pkg[1]!) : path.join(path.dirname(urdfFile), filename);
  if (path.relative(dir, file).startsWith('..')) throw new Error('outside the robot folder');
  return fs.readFileSync(file);
}

/**
 * The robot of profile `name` in `modelsDir`: its profile, its URDF's joints and its description
 * with the meshes inline; throws saying what is wrong.
 */
export function loadRecordingRobot(
  name: string,
  modelsDir = MODELS_DIR,
  source?: ProfileSource,
): RecordingRobot {
  const folder = readRobotFolder(name, modelsDir);
  const dir = path.join(modelsDir, name);
  const urdfFile = path.join(dir, folder.profile.urdf);
  const urdf = folder.urdf ?? fs.readFileSync(urdfFile, 'utf8');
  const parsed = parseUrdfJoints(urdf);
  if (!parsed.ok) throw new Error(`${folder.profile.urdf}: ${parsed.errors.join('; ')}`);
  const description = selfContainedUrdf(urdf, (f) => readFolderMesh(dir, urdfFile, f));
  return { profile: folder.profile, joints: parsed.joints, description, source };
}

export interface FindRobotOptions {
  reader: HistoryReader;
  arm: string;
  /** The range's end: the profile announced last before it. */
  stopMs: number;
  /** `--profile`: wins over what the arm announced. */
  profile?: string;
  /** Asked for the retained announcement when the history has none (null: not asked). */
  broker: BrokerLogin | null;
}

/** The arm's profile name and where it came from, or null when nothing says it. */
export async function findArmProfile(o: FindRobotOptions): Promise<FoundProfile | null> {
  if (o.profile) return { name: o.profile, source: 'flag' };
  const stored = await storedProfile(o.reader, o.arm, o.stopMs);
  if (stored) return { name: stored, source: 'history' };
  const announced = o.broker ? await announcedProfile(o.broker, o.arm) : null;
  return announced ? { name: announced, source: 'broker' } : null;
}

export interface ExportOptions {
  /** Reads InfluxDB: `historyReader(source, language)`. */
  reader: HistoryReader;
  arm: string;
  startMs: number;
  stopMs: number;
  format: ExportFormat;
  out: Writable;
  /** For the MCAP's joint states and link transforms (null = positions and fields only). */
  robot: RecordingRobot | null;
}

export interface ExportSummary {
  points: { servo: number; command: number; ik: number; audit: number };
  /** MCAP: messages per topic. */
  topics: McapCounts;
}

/** Reads the range and writes it to `out` (not ended). */
export async function exportRecording(o: ExportOptions): Promise<ExportSummary> {
  const rec = await readRecording(o.reader, o.arm, o.startMs, o.stopMs);
  const points = {
    servo: rec.servo.length,
    command: rec.command.length,
    ik: rec.ik.length,
    audit: rec.audit.length,
  };
  if (o.format === 'csv') {
    for (const line of csvLines(rec))
      if (!o.out.write(line)) await new Promise((r) => o.out.once('drain', r));
    return { points, topics: {} };
  }
  return { points, topics: await writeMcap(rec, o.robot, streamWritable(o.out)) };
}
