import { describe, expect, it } from 'vitest';
import {
  avcConfigRecord,
  createFlvH264Reader,
  flvFrame,
  flvStart,
  flvTag,
  parseAvcConfig,
  type AccessUnit,
} from '../src/index.ts';

const START = [0, 0, 0, 1];
const SPS = [0x67, 0x42, 0xc0, 0x1e, 0xda, 0x02, 0x80];
const PPS = [0x68, 0xce, 0x3c, 0x80];
const au = (...units: number[][]) => new Uint8Array(units.flatMap((u) => [...START, ...u]));
const key = au([0x09, 0xf0], SPS, PPS, [0x65, 0x88, 0x84, 0x00, 0x33]);
const delta = au([0x41, 0x9a, 0x02, 0x04]);

describe('H.264 access units → FLV', () => {
  it('is read back by the camera server’s own FLV reader: the same frames, keys and times', () => {
    const out: AccessUnit[] = [];
    const reader = createFlvH264Reader({
      onAccessUnit: (a) => out.push(a),
      onError: (e) => expect.fail(e.message),
    });
    reader.feed(flvStart(key)!);
    reader.feed(flvFrame(key, true, 0));
    reader.feed(flvFrame(delta, false, 33));
    reader.feed(flvFrame(delta, false, 0x1_2345_678)); // past 24 bits: the upper byte
    reader.flush();
    expect(out.map((a) => [a.key, a.timestampMs])).toEqual([
      [true, 0],
      [false, 33],
      [false, 0x1_2345_678],
    ]);
    // the key frame comes back with its SPS and PPS in front; the delimiter is left out
    expect([...out[0]!.data]).toEqual([...au(SPS, PPS, [0x65, 0x88, 0x84, 0x00, 0x33])]);
    expect([...out[1]!.data]).toEqual([...delta]);
  });

  it('the configuration record holds the SPS and PPS and their profile', () => {
    const record = avcConfigRecord(new Uint8Array(SPS), [new Uint8Array(PPS)]);
    const config = parseAvcConfig(record)!;
    expect([...config.sps[0]!]).toEqual(SPS);
    expect([...config.pps[0]!]).toEqual(PPS);
    expect(config.lengthSize).toBe(4);
    expect([...record.subarray(1, 4)]).toEqual([0x42, 0xc0, 0x1e]);
  });

  it('a stream cannot start on a frame without parameter sets; a bad time is refused', () => {
    expect(flvStart(delta)).toBeNull();
    expect(() => flvTag(9, -1, new Uint8Array(1))).toThrow(RangeError);
    expect(() => flvTag(9, 1.5, new Uint8Array(1))).toThrow(RangeError);
  });
});
