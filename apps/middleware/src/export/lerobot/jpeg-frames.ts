/**
 * An MJPEG camera's recorded `.mjpeg` segments (../../cameras/jpeg-segmenter.ts) → pieces the
 * concat demuxer places in time (./video.ts): each JPEG is written to the scratch folder as a
 * file of its own, placed at its part's `X-Timestamp` and lasting until the next one (the last
 * one until its segment's end). ffmpeg's `mpjpeg` demuxer reads the segment's pictures but not
 * their stamps, so the times are read here, with the page's multipart reader.
 */
import fs from 'node:fs';
import path from 'node:path';
import { createMultipartParser, MJPEG_BOUNDARY } from '@armtwin/camera';
import type { VideoSegment } from './video.ts';

/** The JPEGs of the `.mjpeg` segments among `segments` as pieces; other segments as they are. */
export function jpegPieces(segments: readonly VideoSegment[], work: string): VideoSegment[] {
  return segments.flatMap((s) => (s.file.endsWith('.mjpeg') ? segmentFrames(s, work) : [s]));
}

function segmentFrames(s: VideoSegment, work: string): VideoSegment[] {
  const frames: { atMs: number; body: Uint8Array }[] = [];
  const parser = createMultipartParser({
    boundary: MJPEG_BOUNDARY,
    onPart: ({ headers, body }) => frames.push({ atMs: Number(headers['x-timestamp']), body }),
    onError: (e) => {
      throw new Error(`${s.file}: not a whole MJPEG segment (${e.message})`);
    },
  });
  parser.feed(fs.readFileSync(s.file));
  parser.flush();
  const stem = path.join(work, path.basename(s.file, '.mjpeg'));
  return frames
    .filter((f) => Number.isFinite(f.atMs))
    .map((f, i, all) => {
      const file = `${stem}-${String(i).padStart(6, '0')}.jpg`;
      fs.writeFileSync(file, f.body);
      return { file, startMs: f.atMs, endMs: all[i + 1]?.atMs ?? s.endMs };
    });
}
