/**
 * Recordings out of armtwin: an arm's stored history over a time range, read from InfluxDB, as
 * MCAP (Foxglove, Lichtblick) or CSV. Used by `armtwin export` and the history API's download.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Writable } from 'node:stream';
import { parseUrdfJoints } from '@armtwin/robot';
import { MODELS_DIR, readRobotFolder } from '@armtwin/motion/robot-folder';
import { csvLines } from './csv.ts';
import { streamWritable, writeMcap, type McapCounts, type RecordingRobot } from './mcap.ts';
import type { HistoryReader } from '../history/reader.ts';
import { readRecording } from './read-recording.ts';

export { readRecording } from './read-recording.ts';
export { writeMcap, streamWritable, type RecordingRobot, type McapCounts } from './mcap.ts';
export { csvLines, CSV_HEADER } from './csv.ts';
export type { Recording } from './recording.ts';

export const EXPORT_FORMATS = ['mcap', 'csv'] as const;
export type ExportFormat = (typeof EXPORT_FORMATS)[number];

/** The robot of profile `name` in `modelsDir`, with its URDF's joints; throws saying what is wrong. */
export function loadRecordingRobot(name: string, modelsDir = MODELS_DIR): RecordingRobot {
  const folder = readRobotFolder(name, modelsDir);
  const urdf =
    folder.urdf ?? fs.readFileSync(path.join(modelsDir, name, folder.profile.urdf), 'utf8');
  const parsed = parseUrdfJoints(urdf);
  if (!parsed.ok) throw new Error(`${folder.profile.urdf}: ${parsed.errors.join('; ')}`);
  return { profile: folder.profile, joints: parsed.joints };
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
