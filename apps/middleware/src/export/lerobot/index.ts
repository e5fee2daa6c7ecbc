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
import { writeCameraVideo, type CameraVideo } from './video.ts';
import { readCameraFolders } from '../../cameras/segment-folder.ts';

export { resample, frameCount, lerobotValue, type Episode, type EpisodeFrames } from './frames.ts';
export { buildDataset, robotType, type DatasetTables } from './dataset.ts';
export { featureStats } from './stats.ts';
export {
  concatList,
  episodeVideoArgs,
  videoKey,
  writeCameraVideo,
  type CameraVideo,
  type VideoInfo,
} from './video.ts';
export { imageStats } from './video-stats.ts';

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
  /**
   * The camera recordings' folder (the middleware's CAMERA_DIR): every camera of the arm recorded
   * over every episode becomes a video feature. Absent: no video.
   */
  camerasDir?: string;
  /** Only these cameras (default: every one recorded over every episode). */
  cameras?: readonly string[];
  ffmpeg?: string;
  ffprobe?: string;
}

export interface LerobotExportSummary {
  episodes: number;
  frames: number;
  tasks: number;
  /** The cameras written as videos. */
  cameras: string[];
  /** Cameras left out, and why. */
  skipped: string[];
}

export async function exportLerobot(o: LerobotExportOptions): Promise<LerobotExportSummary> {
  if (o.episodes.length === 0) throw new RangeError('no episode to export');
  if (fs.existsSync(o.out) && fs.readdirSync(o.out).length > 0)
    throw new Error(`${o.out} is not empty: a dataset is written into a new or empty folder`);
  const start = Math.min(...o.episodes.map((e) => e.startMs));
  const stop = Math.max(...o.episodes.map((e) => e.stopMs));
  const rec = await readRecording(o.reader, o.arm, start - LOOKBACK_MS, stop);
  const frames = resample(o.profile, rec.servo, rec.command, o.episodes, o.fps);
  fs.mkdirSync(path.join(o.out, 'meta'), { recursive: true });
  const { videos, skipped } = await cameraVideos(
    o,
    frames.map((f) => f.timestamps.length),
  );
  const tables = buildDataset(o.profile, frames, o.fps, videos);
  writeParquetFiles(o.out, tables);
  const json = (file: string, value: unknown) =>
    fs.writeFileSync(path.join(o.out, file), `${JSON.stringify(value, null, 4)}\n`);
  json('meta/info.json', tables.info);
  json('meta/stats.json', {
    ...tables.stats,
    ...Object.fromEntries(videos.map((v) => [v.key, v.stats])),
  });
  return {
    episodes: tables.episodes.length,
    frames: tables.data.index.length,
    tasks: tables.tasks.length,
    cameras: videos.map((v) => v.key),
    skipped,
  };
}

/** The videos of every camera recorded over every episode (those asked for, if any). */
async function cameraVideos(
  o: LerobotExportOptions,
  frames: readonly number[],
): Promise<{ videos: CameraVideo[]; skipped: string[] }> {
  const videos: CameraVideo[] = [];
  const skipped: string[] = [];
  if (!o.camerasDir) return { videos, skipped };
  const folders = readCameraFolders(o.camerasDir, o.arm);
  for (const cam of o.cameras ?? [])
    if (!folders.some((f) => f.camId === cam))
      throw new Error(`no recording of camera ${cam} of ${o.arm} in ${o.camerasDir}`);
  const work = fs.mkdtempSync(path.join(o.out, '.video-'));
  try {
    for (const folder of folders) {
      if (o.cameras && !o.cameras.includes(folder.camId)) continue;
      const episodes = o.episodes.map((e, i) => ({ startMs: e.startMs, frames: frames[i]! }));
      const missing = episodes.findIndex(
        (e) =>
          !folder.segments.some(
            (s) => s.endMs >= e.startMs && s.startMs <= e.startMs + (e.frames * 1000) / o.fps,
          ),
      );
      if (missing >= 0) {
        if (o.cameras)
          throw new Error(`camera ${folder.camId} has no recording of episode ${missing}`);
        skipped.push(`${folder.camId} (no recording of episode ${missing})`);
        continue;
      }
      const segments = folder.segments.map((s) => ({ ...s, file: path.join(folder.dir, s.name) }));
      videos.push(
        await writeCameraVideo({
          ffmpeg: o.ffmpeg ?? 'ffmpeg',
          ffprobe: o.ffprobe ?? 'ffprobe',
          camId: folder.camId,
          segments,
          episodes,
          fps: o.fps,
          root: o.out,
          work,
        }),
      );
    }
  } finally {
    fs.rmSync(work, { recursive: true, force: true });
  }
  return { videos, skipped };
}
