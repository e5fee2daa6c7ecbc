import { describe, expect, it } from 'vitest';
import {
  parseSegmentName,
  retentionPlan,
  segmentKind,
  segmentName,
  segmentsBetween,
} from '../src/cameras/index.ts';

const seg = (cam: string, startMs: number, endMs: number, bytes = 100) => ({
  camId: cam,
  name: segmentName(startMs, endMs),
  startMs,
  endMs,
  bytes,
});

describe('camera segment files', () => {
  it('are named by their times, and the names sort as the times', () => {
    const name = segmentName(1_795_777_865_099, 1_795_777_868_085);
    expect(name).toBe('1795777865099-1795777868085.mp4');
    expect(parseSegmentName(name)).toEqual({
      startMs: 1_795_777_865_099,
      endMs: 1_795_777_868_085,
    });
    expect(segmentName(5, 9) < segmentName(1_000_000, 1_000_001)).toBe(true);
    const jpegs = segmentName(1_795_777_865_099, 1_795_777_868_085, 'mjpeg');
    expect(jpegs).toBe('1795777865099-1795777868085.mjpeg');
    expect(parseSegmentName(jpegs)).toEqual({
      startMs: 1_795_777_865_099,
      endMs: 1_795_777_868_085,
    });
    expect([segmentKind(name), segmentKind(jpegs)]).toEqual(['h264', 'mjpeg']);
    for (const bad of [
      'x.mp4',
      '1795777865099-1795777868085.mp4.part',
      '0000000000009-0000000000005.mp4',
      '1795777865099-1795777868085.jpg',
    ])
      expect(parseSegmentName(bad)).toBeNull();
    expect(() => segmentName(10, 5)).toThrow(RangeError);
  });

  it('a range gets every segment holding any frame of it, by time', () => {
    const list = [seg('a', 20, 30), seg('a', 0, 10), seg('a', 10, 20), seg('a', 40, 50)];
    expect(segmentsBetween(list, 15, 35).map((s) => s.startMs)).toEqual([10, 20]);
    expect(segmentsBetween(list, 31, 39)).toEqual([]);
    expect(segmentsBetween(list, 0, 100).map((s) => s.startMs)).toEqual([0, 10, 20, 40]);
  });

  it('retention deletes past the age, then the oldest over every camera until the rest fit', () => {
    const list = [
      seg('b', 50, 60),
      seg('a', 0, 10),
      seg('a', 10, 20),
      seg('b', 20, 30),
      seg('a', 30, 40),
    ];
    const byAge = retentionPlan(list, 1000, { maxAgeMs: 975, maxBytes: 0 });
    expect(byAge.deletions.map((d) => [d.segment.startMs, d.why])).toEqual([
      [0, 'age'],
      [10, 'age'],
    ]);
    const bySize = retentionPlan(list, 1000, { maxAgeMs: 0, maxBytes: 250 });
    expect(bySize.deletions.map((d) => [d.segment.camId, d.segment.startMs, d.why])).toEqual([
      ['a', 0, 'size'],
      ['a', 10, 'size'],
      ['b', 20, 'size'],
    ]);
    expect(bySize.bytesLeft).toBe(200);
    const both = retentionPlan(list, 1000, { maxAgeMs: 985, maxBytes: 300 });
    expect(both.deletions.map((d) => d.why)).toEqual(['age', 'size']);
    expect(retentionPlan(list, 1000, { maxAgeMs: 0, maxBytes: 0 }).deletions).toEqual([]);
  });
});
