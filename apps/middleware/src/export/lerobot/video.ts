/**
 * A camera's recorded segments (../../cameras) → the dataset's video of that camera: one MP4
 * per camera (`videos/observation.images.<cam>/chunk-000/file-000.mp4`), the episodes one after
 * the other, each episode at exactly the dataset's fps with frame k at k/fps from its start, so
 * LeRobot's decoders (torchcodec, PyAV) find each frame at the timestamp of its row.
 *
 * Per episode, ffmpeg reads the segments (an MJPEG camera's: each of their JPEGs, placed at its
 * stamp, ./jpeg-frames.ts) through the concat demuxer with each segment placed at
 * its own start time (`duration` = the time to the next segment, so a gap in the recording stays
 * a gap), the episode's start is moved to time 0, and the `fps` filter (`round=near`) shows in each
 * frame slot the last recorded frame before the slot's midpoint with the next (the nearest frame
 * while they come at the camera's rate; the last one repeated over a gap); `tpad` repeats the
 * last frame if the recording ends before the episode. Re-encoded: H.264 (libx264), yuv420p,
 * a key frame every 2 frames (LeRobot's own choice, for fast random access), CRF 23. Then the
 * episodes' files are joined without re-encoding.
 */
import { execFile } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { promisify } from 'node:util';
import { jpegPieces } from './jpeg-frames.ts';
import { videoStats } from './video-stats.ts';

const run = promisify(execFile);

export const VIDEO_PATH = 'videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4';
export const videoKey = (camId: string): string => `observation.images.${camId}`;
export const videoFile = (key: string): string => `videos/${key}/chunk-000/file-000.mp4`;

export interface VideoSegment {
  file: string;
  startMs: number;
  endMs: number;
}

/**
 * The concat demuxer's list of the segments that hold any of [fromMs, toMs], each placed at its
 * start time from the first one's (`originMs`); null when none does.
 */
export function concatList(
  segments: readonly VideoSegment[],
  fromMs: number,
  toMs: number,
): { text: string; originMs: number } | null {
  const used = segments
    .filter((s) => s.endMs >= fromMs && s.startMs <= toMs)
    .sort((a, b) => a.startMs - b.startMs);
  if (used.length === 0) return null;
  const quote = (f: string) => `'${f.replace(/'/g, "'\\''")}'`;
  const lines = ['ffconcat version 1.0'];
  used.forEach((s, i) => {
    lines.push(`file ${quote(path.resolve(s.file))}`);
    // a picture's own time base is 1/25 s: 1 ms, so each JPEG lands at its stamp
    if (s.file.endsWith('.jpg')) lines.push('option framerate 1000');
    const next = used[i + 1];
    if (next) lines.push(`duration ${((next.startMs - s.startMs) / 1000).toFixed(3)}`);
  });
  return { text: `${lines.join('\n')}\n`, originMs: used[0]!.startMs };
}

/** ffmpeg's arguments for one episode: `frames` frames at `fps` from `offsetS` into the list. */
export function episodeVideoArgs(
  listFile: string,
  offsetS: number,
  frames: number,
  fps: number,
  out: string,
): string[] {
  return [
    ...['-hide_banner', '-nostdin', '-v', 'error', '-y'],
    ...['-f', 'concat', '-safe', '0', '-i', listFile, '-an'],
    '-vf',
    // the episode's start at time 0 first: the fps filter's slots are whole frames from 0
    `setpts=PTS-${offsetS.toFixed(6)}/TB,fps=fps=${fps}:start_time=0:round=near,tpad=stop_mode=clone:stop=-1`,
    ...['-frames:v', String(frames), '-c:v', 'libx264', '-preset', 'veryfast', '-crf', '23'],
    ...['-g', '2', '-pix_fmt', 'yuv420p', '-movflags', '+faststart', out],
  ];
}

/** The `info` of a video feature (LeRobot's `get_video_info` keys). */
export interface VideoInfo {
  'video.height': number;
  'video.width': number;
  'video.codec': string;
  'video.pix_fmt': string;
  'video.is_depth_map': false;
  'video.fps': number;
  'video.channels': number;
  has_audio: false;
}

export interface CameraVideo {
  key: string;
  info: VideoInfo;
  /** Its meta/stats.json entry (./video-stats.ts). */
  stats: Record<string, unknown>;
  /** Each episode's place in the file, s. */
  ranges: { from: number; to: number }[];
}

/**
 * Writes one camera's video of the episodes (each `frames` long, from `startMs`) under `root`;
 * `work` is a scratch folder. Throws when an episode has no recording of this camera.
 */
export async function writeCameraVideo(o: {
  ffmpeg: string;
  ffprobe: string;
  camId: string;
  segments: readonly VideoSegment[];
  episodes: readonly { startMs: number; frames: number }[];
  fps: number;
  root: string;
  work: string;
}): Promise<CameraVideo> {
  const key = videoKey(o.camId);
  const parts: string[] = [];
  const ranges: CameraVideo['ranges'] = [];
  let at = 0;
  for (const [e, ep] of o.episodes.entries()) {
    const stopMs = ep.startMs + (ep.frames * 1000) / o.fps;
    // up to a second past the end: the episode's last frame then has a next one that ends it
    // (the fps filter would take the stream's end at the last JPEG for that frame's end)
    const toMs = stopMs + 1000;
    const used = o.segments.filter((s) => s.endMs >= ep.startMs && s.startMs <= toMs);
    if (used.some((s) => s.file.endsWith('.mjpeg')) && used.some((s) => s.file.endsWith('.mp4')))
      throw new Error(`camera ${o.camId} was recorded as both H.264 and MJPEG in episode ${e}`);
    const list = concatList(jpegPieces(used, o.work), ep.startMs, toMs);
    if (!list) throw new Error(`camera ${o.camId} has no recording of episode ${e}`);
    const listFile = path.join(o.work, `${o.camId}-${e}.ffconcat`);
    fs.writeFileSync(listFile, list.text);
    const part = path.join(o.work, `${o.camId}-${e}.mp4`);
    const offsetS = (ep.startMs - list.originMs) / 1000;
    await run(o.ffmpeg, episodeVideoArgs(listFile, offsetS, ep.frames, o.fps, part));
    parts.push(part);
    ranges.push({ from: at, to: at + ep.frames / o.fps });
    at += ep.frames / o.fps;
  }
  const out = path.join(o.root, videoFile(key));
  fs.mkdirSync(path.dirname(out), { recursive: true });
  if (parts.length === 1) fs.copyFileSync(parts[0]!, out);
  else {
    const joined = path.join(o.work, `${o.camId}-all.ffconcat`);
    const text = parts.map((p) => `file '${path.resolve(p).replace(/'/g, "'\\''")}'`).join('\n');
    fs.writeFileSync(joined, `ffconcat version 1.0\n${text}\n`);
    await run(o.ffmpeg, [
      ...['-hide_banner', '-nostdin', '-v', 'error', '-y', '-f', 'concat', '-safe', '0'],
      ...['-i', joined, '-c', 'copy', '-movflags', '+faststart', out],
    ]);
  }
  const frames = o.episodes.reduce((n, e) => n + e.frames, 0);
  return {
    key,
    info: await probe(o.ffprobe, out, o.fps),
    stats: await videoStats(o.ffmpeg, out, frames),
    ranges,
  };
}

async function probe(ffprobe: string, file: string, fps: number): Promise<VideoInfo> {
  const { stdout } = await run(ffprobe, [
    ...['-v', 'error', '-select_streams', 'v:0', '-show_entries'],
    ...['stream=width,height,codec_name,pix_fmt', '-of', 'json', file],
  ]);
  const s = (JSON.parse(stdout) as { streams: Record<string, string | number>[] }).streams[0]!;
  return {
    'video.height': Number(s.height),
    'video.width': Number(s.width),
    'video.codec': String(s.codec_name),
    'video.pix_fmt': String(s.pix_fmt),
    'video.is_depth_map': false,
    'video.fps': fps,
    'video.channels': 3,
    has_audio: false,
  };
}
