import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { createMultipartParser, MJPEG_BOUNDARY } from '@armtwin/camera';
import { partTime } from '../src/cameras/camera-feeds.ts';
import { JpegSegmenter } from '../src/cameras/jpeg-segmenter.ts';

const jpeg = (n: number) => new Uint8Array([0xff, 0xd8, n, 0xff, 0xd9]);

function parts(file: string) {
  const got: { at: number; body: number[] }[] = [];
  const p = createMultipartParser({
    boundary: MJPEG_BOUNDARY,
    onPart: (part) => got.push({ at: Number(part.headers['x-timestamp']), body: [...part.body] }),
  });
  p.feed(fs.readFileSync(file));
  return { got, closed: p.closed };
}

describe('MJPEG segments', () => {
  it('hold the JPEGs as given with their times, cut at the first frame past the length, named by their times', async () => {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'jpeg-seg-'));
    const segments: { name: string; startMs: number; endMs: number }[] = [];
    const s = new JpegSegmenter({
      dir,
      segmentS: 1,
      baseMs: 5000,
      onSegment: (x) => segments.push(x),
      onProblem: (kind) => {
        throw new Error(kind);
      },
    });
    for (const [i, at] of [5000, 5400, 5800, 6000, 6400].entries()) s.write(jpeg(i), at);
    expect(fs.readdirSync(dir)).toEqual(['0000000005000-0000000006000.mjpeg', '5000-1.part']);
    await s.end();
    expect(segments.map((x) => [x.name, x.startMs, x.endMs])).toEqual([
      ['0000000005000-0000000006000.mjpeg', 5000, 6000],
      ['0000000006000-0000000006800.mjpeg', 6000, 6800], // last frame + the step before it
    ]);
    expect(fs.readdirSync(dir)).toEqual(segments.map((x) => x.name));
    const first = parts(path.join(dir, segments[0]!.name));
    expect(first.closed).toBe(true);
    expect(first.got).toEqual([
      { at: 5000, body: [...jpeg(0)] },
      { at: 5400, body: [...jpeg(1)] },
      { at: 5800, body: [...jpeg(2)] },
    ]);
  });

  it('take a part’s X-Timestamp as the frame’s time only when it is epoch ms near the clock', () => {
    const now = 1_795_777_865_000;
    expect(partTime('1795777864967', now)).toBe(1_795_777_864_967);
    expect(partTime('1795777864967.5', now)).toBe(1_795_777_864_967.5);
    expect(partTime('12345.678901', now)).toBeNull(); // ustreamer's monotonic seconds
    expect(partTime(undefined, now)).toBeNull();
    expect(partTime('soon', now)).toBeNull();
  });
});
