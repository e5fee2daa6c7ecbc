/**
 * `armtwin export --format lerobot`: episodes of an arm's stored history as a LeRobot v3.0
 * dataset folder (frames.ts resamples, dataset.ts lays out, parquet.ts writes). Reads the
 * history once over all episodes, from LOOKBACK_MS before the first so the first frame holds
 * the position and command in force when it starts.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Profile } from '@armtwin/robot';
import type { HistoryReader } from '../../history/reader.ts';
import { readRecording } from '../read-recording.ts';
import { buildDataset } from './dataset.ts';
import { resample, type Episode } from './frames.ts';
import { writeParquetFiles } from './parquet.ts';

export { resample, frameCount, lerobotValue, type Episode, type EpisodeFrames } from './frames.ts';
export { buildDataset, robotType, type DatasetTables } from './dataset.ts';
export { featureStats } from './stats.ts';

/** How far before an episode the position and command in force are looked for. */
export const LOOKBACK_MS = 10_000;
export const DEFAULT_FPS = 30;

export interface LerobotExportOptions {
  reader: HistoryReader;
  arm: string;
  profile: Profile;
  episodes: readonly Episode[];
  fps: number;
  /** The dataset's folder: created; refused if it holds anything. */
  out: string;
}

export interface LerobotExportSummary {
  episodes: number;
  frames: number;
  tasks: number;
}

export async function exportLerobot(o: LerobotExportOptions): Promise<LerobotExportSummary> {
  if (o.episodes.length === 0) throw new RangeError('no episode to export');
  if (fs.existsSync(o.out) && fs.readdirSync(o.out).length > 0)
    throw new Error(`${o.out} is not empty: a dataset is written into a new or empty folder`);
  const start = Math.min(...o.episodes.map((e) => e.startMs));
  const stop = Math.max(...o.episodes.map((e) => e.stopMs));
  const rec = await readRecording(o.reader, o.arm, start - LOOKBACK_MS, stop);
  const frames = resample(o.profile, rec.servo, rec.command, o.episodes, o.fps);
  const tables = buildDataset(o.profile, frames, o.fps);
  fs.mkdirSync(path.join(o.out, 'meta'), { recursive: true });
  writeParquetFiles(o.out, tables);
  const json = (file: string, value: unknown) =>
    fs.writeFileSync(path.join(o.out, file), `${JSON.stringify(value, null, 4)}\n`);
  json('meta/info.json', tables.info);
  json('meta/stats.json', tables.stats);
  return {
    episodes: tables.episodes.length,
    frames: tables.data.index.length,
    tasks: tables.tasks.length,
  };
}
