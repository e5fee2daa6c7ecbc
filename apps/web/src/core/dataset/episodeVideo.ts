/**
 * Where an imported LeRobot episode's camera video is, and how the History replay's clock maps
 * onto it (docs/dataset.md, "Import"). LeRobot keeps one feature per camera,
 * `observation.images.<cam>` with dtype `video`:
 * - v3.0: one MP4 per camera and chunk holding many episodes back to back. The episode's rows in
 *   meta/episodes say which file (`videos/<key>/chunk_index`, `file_index`) and where in it
 *   (`from_timestamp`, `to_timestamp`, s). LeRobot decodes frame t of the episode at media time
 *   from_timestamp + t.
 * - v2.1: one MP4 per episode (`episode_chunk` = index ÷ `chunks_size`), media time t.
 * The file's name comes from info.json's `video_path` template. The replay shows the clip as a
 * recorded segment (core/replay/videoAt.ts), so ReplayVideo.tsx plays it like a camera
 * recording. Pure.
 */
import type { RecordedSegment } from '../replay/videoAt.ts';

/** One camera's clip of one episode. */
export interface EpisodeClip {
  /** The feature, `observation.images.front`. */
  key: string;
  /** The MP4's path from the dataset's root. */
  path: string;
  /** The episode's first and last media time in that file, s. */
  fromS: number;
  toS: number;
}

/** The parts of meta/info.json read here. */
export interface VideoInfo {
  fps?: number;
  chunks_size?: number;
  video_path?: string | null;
  features?: Record<string, { dtype?: string; info?: Record<string, unknown> | null }>;
}

/** The codec info.json names for a video feature (`info["video.codec"]`, e.g. `av1`), or null. */
export function videoCodec(info: VideoInfo, key: string): string | null {
  const codec = info.features?.[key]?.info?.['video.codec'];
  return typeof codec === 'string' && codec !== '' ? codec : null;
}

/** The features LeRobot stores as video, in info.json's order. */
export const videoKeys = (info: VideoInfo): string[] =>
  Object.entries(info.features ?? {})
    .filter(([, f]) => f.dtype === 'video')
    .map(([k]) => k);

/** Python's `str.format` for the templates LeRobot writes: `{name}` and `{name:03d}`. */
export function formatPath(template: string, values: Record<string, string | number>): string {
  return template.replace(/\{(\w+)(?::0?(\d+)d)?\}/g, (_, name: string, width?: string) => {
    const v = values[name];
    if (v === undefined) throw new Error(`video_path ${template} needs ${name}`);
    return width ? String(v).padStart(Number(width), '0') : String(v);
  });
}

/** The meta/episodes columns of a v3.0 video feature. */
export const v3Columns = (key: string): string[] =>
  ['chunk_index', 'file_index', 'from_timestamp', 'to_timestamp'].map((c) => `videos/${key}/${c}`);

/**
 * A v3.0 episode's clip of `key` from its meta/episodes row (column → value, as read from
 * Parquet); why not where the row lacks a column.
 */
export function v3Clip(
  info: VideoInfo,
  key: string,
  row: Record<string, unknown>,
): EpisodeClip | string {
  const [chunk, file, from, to] = v3Columns(key).map((c) => Number(row[c] ?? NaN));
  if (![chunk, file, from, to].every(Number.isFinite))
    return `meta/episodes has no ${v3Columns(key).join(', ')} for episode ${String(row.episode_index)}`;
  const template =
    info.video_path ?? 'videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4';
  const path = formatPath(template, { video_key: key, chunk_index: chunk!, file_index: file! });
  return { key, path, fromS: from!, toS: to! };
}

/** A v2.1 episode's clip of `key`: its own file, `frames` long at the dataset's fps. */
export function v21Clip(
  info: VideoInfo,
  key: string,
  episode: number,
  frames: number,
): EpisodeClip {
  const template =
    info.video_path ??
    'videos/chunk-{episode_chunk:03d}/{video_key}/episode_{episode_index:06d}.mp4';
  const path = formatPath(template, {
    video_key: key,
    episode_index: episode,
    episode_chunk: Math.floor(episode / (info.chunks_size ?? 1000)),
  });
  return { key, path, fromS: 0, toS: frames / (info.fps ?? 30) };
}

/**
 * The clip as a recorded segment on the replay's clock, whose episode starts at `startMs`
 * (episode time t at startMs + 1000 t): media time from + t, plus half a frame, so the paused
 * picture is the frame of t and not the one before it (a <video> shows the last frame at or
 * before its currentTime, and the dataset's float32 timestamps may fall a hair short of it).
 */
export function clipSegment(clip: EpisodeClip, startMs: number, fps: number): RecordedSegment {
  const half = 500 / fps;
  return {
    name: clip.path,
    startMs: startMs - clip.fromS * 1000 - half,
    endMs: startMs + (clip.toS - clip.fromS) * 1000 - half,
  };
}

/** The camera's name for a feature key: `observation.images.front` → `front`. */
export const cameraName = (key: string): string => key.replace(/^observation\.images\./, '');
