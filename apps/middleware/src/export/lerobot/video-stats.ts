/**
 * A video feature's statistics for meta/stats.json, as LeRobot keeps them for a camera: per
 * channel (shape [3, 1, 1]) min, max, mean, std and the quantiles of the pixels in 0–1, `count`
 * the frames sampled. Like LeRobot's own writer, from a sample of frames (at most
 * `MAX_SAMPLED_FRAMES`, evenly spread) scaled down (`SAMPLE_WIDTH`): `lerobot-train` reads them
 * to normalise the images (and overwrites them with ImageNet's by default, but needs them there).
 */
import { execFile } from 'node:child_process';
import { promisify } from 'node:util';
import { featureStats, STAT_NAMES } from './stats.ts';

const run = promisify(execFile);
export const MAX_SAMPLED_FRAMES = 64;
export const SAMPLE_WIDTH = 80;
export const SAMPLE_HEIGHT = 60;

/** Stats of interleaved RGB bytes (`frames` pictures), each stat shaped [3, 1, 1]. */
export function imageStats(rgb: Uint8Array, frames: number): Record<string, unknown> {
  const rows: number[][] = [];
  for (let i = 0; i + 2 < rgb.length; i += 3)
    rows.push([rgb[i]! / 255, rgb[i + 1]! / 255, rgb[i + 2]! / 255]);
  const s = featureStats(rows);
  const out: Record<string, unknown> = {};
  for (const name of STAT_NAMES)
    out[name] = name === 'count' ? [frames] : s[name].map((v) => [[v]]);
  return out;
}

/** The stats of a video file of `frames` frames. */
export async function videoStats(
  ffmpeg: string,
  file: string,
  frames: number,
): Promise<Record<string, unknown>> {
  const step = Math.max(1, Math.ceil(frames / MAX_SAMPLED_FRAMES));
  const { stdout } = await run(
    ffmpeg,
    [
      ...['-hide_banner', '-nostdin', '-v', 'error', '-i', file, '-fps_mode', 'passthrough'],
      ...['-vf', `select=not(mod(n\\,${step})),scale=${SAMPLE_WIDTH}:${SAMPLE_HEIGHT}`],
      ...['-f', 'rawvideo', '-pix_fmt', 'rgb24', '-'],
    ],
    { encoding: 'buffer', maxBuffer: 64 * 1024 * 1024 },
  );
  const sampled = stdout.length / (SAMPLE_WIDTH * SAMPLE_HEIGHT * 3);
  return imageStats(new Uint8Array(stdout), sampled);
}
