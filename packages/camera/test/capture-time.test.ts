import { describe, expect, it } from 'vitest';
import { captureTime, MAX_STAMP_SKEW_MS, unwrapStamp, wallClockStamp } from '../src/index.ts';

/** 2026-11-27, an epoch ms whose low 31 bits are far from wrapping. */
const NOW = 1_795_799_240_868;
const low = (ms: number, bits: number) => ms % 2 ** bits;

describe('a muxed time stamp put back on the wall clock', () => {
  it("FLV's 31 bits and SMJPEG's 32 give back the frame's epoch ms, a few ms or seconds old", () => {
    for (const age of [0, 3, 33, 2_500, 9_999])
      for (const bits of [31, 32])
        expect(unwrapStamp(low(NOW - age, bits), NOW), `${age} ms, ${bits} bits`).toBe(NOW - age);
    // a stamp cut to 32 bits is read modulo 2^31 all the same
    expect(unwrapStamp(2 ** 31 + low(NOW - 40, 31), NOW)).toBe(NOW - 40);
  });

  it('across a wrap of the low bits, either way', () => {
    const span = 2 ** 31;
    const wrapAt = Math.ceil(NOW / span) * span; // the next instant whose low 31 bits are 0
    // the clock just wrapped, the frame was taken just before
    expect(unwrapStamp(span - 20, wrapAt + 5)).toBe(wrapAt - 20);
    // the frame was taken just after the wrap, the clock reads a ms earlier (rounding)
    expect(unwrapStamp(1, wrapAt - 1)).toBe(wrapAt + 1);
    expect(captureTime(span - 20, wrapAt + 5)).toBe(wrapAt - 20);
  });

  it('a stamp that is not the wall clock is refused: the frame is stamped on arrival', () => {
    // a source whose times start at 0 (ffmpeg shifting it, or an RTSP camera's own clock)
    expect(captureTime(0, NOW)).toBeNull();
    expect(captureTime(33, NOW)).toBeNull();
    expect(captureTime(low(NOW - MAX_STAMP_SKEW_MS - 1, 31), NOW)).toBeNull();
    expect(captureTime(low(NOW + MAX_STAMP_SKEW_MS + 1, 31), NOW)).toBeNull();
    expect(captureTime(low(NOW - MAX_STAMP_SKEW_MS, 31), NOW)).toBe(NOW - MAX_STAMP_SKEW_MS);
  });

  it('wallClockStamp: epoch ms within the skew of the clock, else null', () => {
    expect(wallClockStamp(NOW - 5, NOW)).toBe(NOW - 5);
    expect(wallClockStamp(NOW + 0.5, NOW)).toBe(NOW + 0.5);
    expect(wallClockStamp(12_345.678, NOW)).toBeNull(); // ustreamer's monotonic seconds
    expect(wallClockStamp(Number.NaN, NOW)).toBeNull();
  });
});
