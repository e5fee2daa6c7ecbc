/**
 * Reads a recorded `.mjpeg` segment (docs/cameras-recording.md) the way the page and the export
 * do, with `@armtwin/camera`'s multipart reader: each part's time (`X-Timestamp`, epoch ms) and
 * its JPEG, and whether the file ended with its closing boundary (it is whole). `jpegs` is every
 * JPEG one after the other, for `ffmpeg -f jpeg_pipe -i -` (ffmpeg's own `mpjpeg` demuxer
 * reports "Invalid data" at the end of any such file, so a test cannot hold it to silence).
 */
import fs from 'node:fs';
import { createMultipartParser, MJPEG_BOUNDARY } from '@armtwin/camera';

export function readMjpegSegment(file: string): {
  times: number[];
  jpegs: Buffer;
  closed: boolean;
  errors: string[];
} {
  const times: number[] = [];
  const bodies: Uint8Array[] = [];
  const errors: string[] = [];
  const parser = createMultipartParser({
    boundary: MJPEG_BOUNDARY,
    onPart: (p) => {
      times.push(Number(p.headers['x-timestamp']));
      bodies.push(p.body);
    },
    onError: (e) => errors.push(`${e.kind}: ${e.message}`),
  });
  parser.feed(fs.readFileSync(file));
  const closed = parser.closed;
  parser.flush();
  return { times, jpegs: Buffer.concat(bodies), closed, errors };
}
