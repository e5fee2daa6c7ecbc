import { describe, expect, test } from 'vitest';
import { selfTimes, shortUrl, type CpuProfile } from '../lib/cpuprofile.ts';

const frame = (functionName: string, url = '', lineNumber = 0) => ({
  functionName,
  url,
  lineNumber,
});

describe('a .cpuprofile summed by function', () => {
  test('self time is the samples a function was on top of, as shares, largest first', () => {
    const p: CpuProfile = {
      nodes: [
        { id: 1, callFrame: frame('(root)') },
        { id: 2, callFrame: frame('handle', 'file:///repo/apps/middleware/src/ingest.ts', 9) },
        { id: 3, callFrame: frame('parse', 'file:///repo/node_modules/mqtt-packet/parser.js', 36) },
        { id: 4, callFrame: frame('handle', 'file:///repo/apps/middleware/src/ingest.ts', 9) },
        { id: 5, callFrame: frame('(garbage collector)') },
      ],
      samples: [2, 3, 4, 5, 2, 99],
      timeDeltas: [1000, 2000, 3000, 1000, 1000, 5000],
    };
    const { totalMs, rows } = selfTimes(p, '/repo');
    expect(totalMs).toBe(8); // the sample of an unknown node is not counted
    expect(rows).toEqual([
      { fn: 'handle (apps/middleware/src/ingest.ts:10)', selfMs: 5, share: 5 / 8 },
      { fn: 'parse (mqtt-packet/parser.js:37)', selfMs: 2, share: 2 / 8 },
      { fn: '(garbage collector)', selfMs: 1, share: 1 / 8 },
    ]);
  });

  test('paths: a package by its name, the repository relative, others as they are', () => {
    expect(shortUrl('file:///r/node_modules/a/node_modules/b/x.js', '/r')).toBe('b/x.js');
    expect(shortUrl('/r/bench/x.ts', '/r')).toBe('bench/x.ts');
    expect(shortUrl('node:zlib', '/r')).toBe('node:zlib');
  });
});
