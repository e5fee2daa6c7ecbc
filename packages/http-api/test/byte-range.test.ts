import { describe, expect, it } from 'vitest';
import { byteRange } from '../src/byte-range.ts';

describe('one byte range of a file', () => {
  it('first-last, first- and -suffix, clipped to the file', () => {
    expect(byteRange('bytes=0-99', 1000)).toEqual({ start: 0, end: 99 });
    expect(byteRange('bytes=500-', 1000)).toEqual({ start: 500, end: 999 });
    expect(byteRange('bytes=-100', 1000)).toEqual({ start: 900, end: 999 });
    expect(byteRange('bytes=-5000', 1000)).toEqual({ start: 0, end: 999 });
    expect(byteRange('bytes=900-5000', 1000)).toEqual({ start: 900, end: 999 });
    expect(byteRange(' bytes = 1 - 2 ', 1000)).toEqual({ start: 1, end: 2 });
  });

  it('past the end, or an empty suffix: unsatisfiable', () => {
    expect(byteRange('bytes=1000-', 1000)).toBe('unsatisfiable');
    expect(byteRange('bytes=1000-2000', 1000)).toBe('unsatisfiable');
    expect(byteRange('bytes=-0', 1000)).toBe('unsatisfiable');
    expect(byteRange('bytes=-10', 0)).toBe('unsatisfiable');
  });

  it('anything else is ignored: the whole file', () => {
    for (const h of [
      undefined,
      '',
      'bytes=-',
      'bytes=5-2',
      'items=0-1',
      'bytes=0-1,5-6',
      'bytes=a-b',
    ])
      expect(byteRange(h, 1000), String(h)).toBeNull();
  });
});
