import { describe, expect, it } from 'vitest';
import { createSmjpegParser, type SmjpegParserOptions } from '../src/index.ts';
import { concat, feedings, toHex } from './hex.ts';

const ascii = (s: string) => Uint8Array.from(s, (c) => c.charCodeAt(0));
const u32 = (n: number) => Uint8Array.of(n >>> 24, (n >>> 16) & 255, (n >>> 8) & 255, n & 255);
const u16 = (n: number) => Uint8Array.of(n >>> 8, n & 255);

/** What ffmpeg's `-f smjpeg` writes before the frames: magic, version, duration, _TXT, _VID, HEND. */
const HEADER = concat([
  Uint8Array.of(0x00, 0x0a),
  ascii('SMJPEG'),
  u32(0),
  u32(0),
  ascii('_TXT'),
  u32(23),
  ascii('encoder = Lavf59.27.100'),
  ascii('_VID'),
  u32(12),
  u32(0),
  u16(640),
  u16(480),
  ascii('JFIF'),
  ascii('HEND'),
]);
const jpeg = (n: number) => Uint8Array.of(0xff, 0xd8, n, n, n, 0xff, 0xd9);
const chunk = (tag: string, ts: number, data: Uint8Array) =>
  concat([ascii(tag), u32(ts), u32(data.length), data]);

function run(chunks: Uint8Array[], options: Partial<SmjpegParserOptions> = {}) {
  const frames: { jpeg: string; timestampMs: number }[] = [];
  const errors: string[] = [];
  const p = createSmjpegParser({
    onFrame: (f) => frames.push({ jpeg: toHex(f.jpeg), timestampMs: f.timestampMs }),
    onError: (e) => errors.push(e.kind),
    ...options,
  });
  for (const c of chunks) p.feed(c);
  p.flush();
  return { frames, errors };
}

describe('SMJPEG → JPEGs with their time stamps, fed every way', () => {
  it('each video frame with its 32-bit ms stamp; sound chunks skipped; DONE ends it', () => {
    const stream = concat([
      HEADER,
      chunk('vidD', 502_966_454, jpeg(1)),
      chunk('sndD', 502_966_460, Uint8Array.of(9, 9)),
      chunk('vidD', 0xfffffff0, jpeg(2)), // the top bit set: read as unsigned
      ascii('DONE'),
    ]);
    for (const [how, chunks] of feedings([stream]))
      expect(run(chunks), how).toEqual({
        frames: [
          { jpeg: toHex(jpeg(1)), timestampMs: 502_966_454 },
          { jpeg: toHex(jpeg(2)), timestampMs: 0xfffffff0 },
        ],
        errors: [],
      });
  });

  it('not SMJPEG, a chunk it does not know, a frame over the bound: said once, then nothing', () => {
    expect(run([ascii('FLV\x01\x01\0\0\0\x09\0\0\0\0\0\0\0')]).errors).toEqual(['bad-header']);
    const bad = run([concat([HEADER, chunk('vidD', 1, jpeg(1)), chunk('junk', 2, jpeg(2))])]);
    expect(bad).toEqual({
      frames: [{ jpeg: toHex(jpeg(1)), timestampMs: 1 }],
      errors: ['bad-chunk'],
    });
    const big = run([concat([HEADER, chunk('vidD', 1, new Uint8Array(100))])], {
      maxFrameBytes: 64,
    });
    expect(big).toEqual({ frames: [], errors: ['frame-too-large'] });
    const preamble = HEADER.subarray(0, 16);
    expect(run([concat([preamble, ascii('_XYZ'), u32(0), ascii('HEND')])]).errors).toEqual([
      'bad-header',
    ]);
  });

  it('a stream cut inside a frame is reported at its end; reset() starts a new stream', () => {
    const whole = concat([HEADER, chunk('vidD', 7, jpeg(3))]);
    expect(run([whole.subarray(0, whole.length - 2)])).toEqual({
      frames: [],
      errors: ['truncated'],
    });
    const frames: number[] = [];
    const p = createSmjpegParser({ onFrame: (f) => frames.push(f.timestampMs) });
    p.feed(whole.subarray(0, HEADER.length + 5));
    p.reset();
    p.feed(whole);
    expect(frames).toEqual([7]);
    expect(p.bufferedBytes).toBe(0);
    expect(p.failed).toBe(false);
  });
});
