/**
 * An MJPEG camera's recorded `.mjpeg` segment (docs/cameras-recording.md: its JPEGs as served,
 * one multipart part each with `X-Timestamp`, the frame's epoch ms) → its frames by time, and
 * the frame a replay instant shows: the last one at or before it. Pure; the History replay
 * (ui/panels/History/ReplayJpegs.ts) draws it in an <img>, as the MJPEG has no <video> codec.
 */
import { createMultipartParser, MJPEG_BOUNDARY } from '@armtwin/camera/client';
import { lastAtOrBefore } from './videoAt.ts';

export interface JpegFrame {
  /** Epoch ms. */
  atMs: number;
  jpeg: Uint8Array;
}

export function isJpegSegment(name: string): boolean {
  return name.endsWith('.mjpeg');
}

/** The frames of a segment's bytes, by time (parts without a time are left out). */
export function readJpegFrames(bytes: Uint8Array): JpegFrame[] {
  const frames: JpegFrame[] = [];
  const parser = createMultipartParser({
    boundary: MJPEG_BOUNDARY,
    onPart: ({ headers, body }) => {
      const atMs = Number(headers['x-timestamp']);
      if (headers['x-timestamp'] && Number.isFinite(atMs)) frames.push({ atMs, jpeg: body });
    },
  });
  parser.feed(bytes);
  parser.flush();
  return frames.sort((a, b) => a.atMs - b.atMs);
}

/** Index of the frame shown at `t` (epoch ms): the last at or before it; -1 before the first. */
export function jpegFrameAt(frames: readonly JpegFrame[], t: number): number {
  return lastAtOrBefore(frames, t, (f) => f.atMs);
}
