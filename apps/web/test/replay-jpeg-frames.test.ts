import { describe, expect, it } from 'vitest';
import { mjpegPart } from '@armtwin/camera';
import { isJpegSegment, jpegFrameAt, readJpegFrames } from '../src/core/replay/jpegFrames.ts';

const jpeg = (n: number) => new Uint8Array([0xff, 0xd8, n, 0xff, 0xd9]);
/** A recorded `.mjpeg` segment as the middleware writes it: the served parts, then the close. */
function segment(times: number[]): Uint8Array {
  const parts = times.map((t, i) => mjpegPart(jpeg(i), t, i));
  const close = new TextEncoder().encode('--armtwin-frame--\r\n');
  const out = new Uint8Array([...parts.flatMap((p) => [...p]), ...close]);
  return out;
}

describe("an MJPEG camera's recorded segment in the replay", () => {
  it('is read into its frames with their times, and each instant shows the last frame at or before it', () => {
    const frames = readJpegFrames(segment([1000, 1033, 1067]));
    expect(frames.map((f) => [f.atMs, [...f.jpeg]])).toEqual([
      [1000, [...jpeg(0)]],
      [1033, [...jpeg(1)]],
      [1067, [...jpeg(2)]],
    ]);
    expect([999, 1000, 1032, 1033, 1066, 5000].map((t) => jpegFrameAt(frames, t))).toEqual([
      -1, 0, 0, 1, 1, 2,
    ]);
    expect(isJpegSegment('0000000001000-0000000001100.mjpeg')).toBe(true);
    expect(isJpegSegment('0000000001000-0000000001100.mp4')).toBe(false);
  });
});
