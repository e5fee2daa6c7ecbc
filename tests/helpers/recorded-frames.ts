/**
 * The frames a middleware recorded of a camera (docs/cameras-recording.md), read back from its
 * segment files for a test: each frame's recorded time and the clock ffmpeg's test source drew
 * in it (the time stripe, decoded by ffmpeg from the segment itself). MP4 segments are named
 * `<fromMs>-<toMs>.mp4` and timed by their packets; MJPEG ones by their parts' stamps.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { expect } from 'vitest';
import { readTimeStripe, timeStripeLayout } from '@armtwin/camera';
import { readMjpegSegment } from './mjpeg-segment.ts';

/** The test source's picture size. */
export const [W, H] = [640, 480];
/** The rows of the time stripe at the bottom of a picture. */
export const BAND = timeStripeLayout(W, H).blockH;

/** The epoch ms of the time stripe in a decoded frame's bottom rows (gray, or base64 of it). */
export function stripeOf(band: Uint8Array | string): number | null {
  const luma = new Uint8Array(W * H);
  luma.set(typeof band === 'string' ? Buffer.from(band, 'base64') : band, (H - BAND) * W);
  return readTimeStripe(luma, W, H);
}

/** Epoch ms of each frame of a segment: of an MP4 its name + each packet's time, of an MJPEG one its parts' stamps. */
export function segmentTimes(file: string, from: number): number[] {
  if (file.endsWith('.mjpeg')) return readMjpegSegment(file).times;
  return execFileSync('ffprobe', [
    ...['-v', 'error', '-select_streams', 'v', '-show_entries', 'packet=pts_time'],
    ...['-of', 'csv=p=0', file],
  ])
    .toString()
    .trim()
    .split('\n')
    .map((t) => from + Number(t) * 1000);
}

/**
 * Every frame recorded in `folder` (one camera's segments) by segments that overlap
 * `startMs`..`stopMs` widened by 1 s: its time and its clock.
 */
export function recordedFrames(
  folder: string,
  startMs: number,
  stopMs: number,
): { atMs: number; clock: number }[] {
  const out: { atMs: number; clock: number }[] = [];
  for (const name of fs.readdirSync(folder).sort()) {
    const [from, to] = name
      .replace(/\.\w+$/, '')
      .split('-')
      .map(Number) as [number, number];
    if (to < startMs - 1000 || from > stopMs + 1000) continue;
    const file = path.join(folder, name);
    const times = segmentTimes(file, from);
    const mjpeg = name.endsWith('.mjpeg');
    const input = mjpeg ? ['-f', 'jpeg_pipe', '-i', '-'] : ['-i', file];
    const bands = execFileSync(
      'ffmpeg',
      [
        ...['-v', 'error', ...input, '-fps_mode', 'passthrough'],
        ...['-vf', `crop=${W}:${BAND}:0:${H - BAND}`, '-f', 'rawvideo', '-pix_fmt', 'gray', '-'],
      ],
      { maxBuffer: 256 * 1024 * 1024, input: mjpeg ? readMjpegSegment(file).jpegs : undefined },
    );
    expect(bands.length).toBe(times.length * W * BAND);
    times.forEach((atMs, k) => {
      const clock = stripeOf(bands.subarray(k * W * BAND, (k + 1) * W * BAND));
      expect(clock, `${name} frame ${k}`).not.toBeNull();
      out.push({ atMs, clock: clock! });
    });
  }
  return out;
}
