import { describe, expect, it } from 'vitest';
import { needsSeek, videoAt } from '../src/core/replay/videoAt.ts';

const SEGMENTS = [
  { name: 'a', startMs: 1000, endMs: 3000 },
  { name: 'b', startMs: 3000, endMs: 5000 },
  // a gap: 5000…8000 (the camera server was down)
  { name: 'c', startMs: 8000, endMs: 9500 },
];

describe('videoAt: the recorded segment and media time of a replay instant', () => {
  it('finds the segment covering the instant and the offset into it', () => {
    expect(videoAt(SEGMENTS, 1000)).toEqual({ segment: SEGMENTS[0], offsetS: 0 });
    expect(videoAt(SEGMENTS, 2500)).toEqual({ segment: SEGMENTS[0], offsetS: 1.5 });
    // a boundary belongs to the segment that starts there
    expect(videoAt(SEGMENTS, 3000)).toEqual({ segment: SEGMENTS[1], offsetS: 0 });
    expect(videoAt(SEGMENTS, 9500)).toEqual({ segment: SEGMENTS[2], offsetS: 1.5 });
  });

  it('answers null before the first segment, in a gap and after the last', () => {
    expect(videoAt(SEGMENTS, 999)).toBeNull();
    expect(videoAt(SEGMENTS, 5001)).toBeNull();
    expect(videoAt(SEGMENTS, 7999)).toBeNull();
    expect(videoAt(SEGMENTS, 9501)).toBeNull();
    expect(videoAt([], 2000)).toBeNull();
  });
});

describe('needsSeek', () => {
  it('paused: any drift beyond a millisecond moves the video', () => {
    expect(needsSeek(1.5, 1.5, false)).toBe(false);
    expect(needsSeek(1.5, 1.502, false)).toBe(true);
  });

  it('playing: small drift is let be, a jump (a scrub) moves it', () => {
    expect(needsSeek(1.5, 1.6, true)).toBe(false);
    expect(needsSeek(1.5, 3, true)).toBe(true);
    expect(needsSeek(NaN, 0, true)).toBe(true);
  });
});
