import { describe, expect, it } from 'vitest';
import { createJpegSplitter, type JpegSplitterError } from '../src/index.ts';
import { feedings, fromHex, toHex } from './hex.ts';
import vectors from './vectors/jpeg-splitter.json' with { type: 'json' };

interface Vector {
  name: string;
  chunks: string[];
  frames: string[];
  errors: string[];
  maxFrameBytes?: number;
}

function run(chunks: Uint8Array[], maxFrameBytes?: number) {
  const frames: string[] = [];
  const errors: JpegSplitterError[] = [];
  const splitter = createJpegSplitter({
    onFrame: (f) => frames.push(toHex(f)),
    onError: (e) => errors.push(e),
    ...(maxFrameBytes ? { maxFrameBytes } : {}),
  });
  for (const c of chunks) splitter.feed(c);
  splitter.flush();
  return { frames, errors: errors.map((e) => e.kind) };
}

describe('JPEG splitter vectors, fed every way', () => {
  for (const v of vectors as Vector[]) {
    it(v.name, () => {
      for (const [how, chunks] of feedings(v.chunks.map(fromHex)))
        expect(run(chunks, v.maxFrameBytes), how).toEqual({ frames: v.frames, errors: v.errors });
    });
  }
});

describe('JPEG splitter', () => {
  it('hands out an image the moment its EOI arrives, not at the next image', () => {
    const frames: Uint8Array[] = [];
    const s = createJpegSplitter({ onFrame: (f) => frames.push(f) });
    s.feed(fromHex((vectors as Vector[])[0]!.frames[0]!));
    expect(frames).toHaveLength(1);
    expect(s.bufferedBytes).toBe(0);
  });

  it('never holds more than maxFrameBytes of a runaway image', () => {
    const errors: string[] = [];
    const s = createJpegSplitter({
      onFrame: () => {},
      onError: (e) => errors.push(e.kind),
      maxFrameBytes: 1000,
    });
    s.feed(fromHex('FFD8FFDA0008010100003F00'));
    for (let i = 0; i < 100; i++) {
      s.feed(new Uint8Array(100).fill(0x11));
      expect(s.bufferedBytes).toBeLessThanOrEqual(1000);
    }
    expect(errors).toEqual(['frame-too-large']);
  });

  it('reset() forgets a partial image without a report', () => {
    const errors: string[] = [];
    const s = createJpegSplitter({ onFrame: () => {}, onError: (e) => errors.push(e.kind) });
    s.feed(fromHex('FFD8FFE0'));
    s.reset();
    s.flush();
    expect(errors).toEqual([]);
  });
});
