import { describe, expect, test } from 'vitest';
import { Segment, type SegmentIo } from '../src/spool-segment.ts';

/** The calls a segment makes, each finished when the test says (libuv's pool, scripted). */
function scriptedIo() {
  const calls: string[] = [];
  const waiting: (() => void)[] = [];
  const io: SegmentIo = {
    fdatasync: (fd, cb) => {
      calls.push(`fdatasync ${fd}`);
      waiting.push(() => cb(null));
    },
    close: (fd, cb) => {
      calls.push(`close ${fd}`);
      waiting.push(() => cb(null));
    },
  };
  const finishOne = () => waiting.shift()!();
  return { io, calls, finishOne, busy: () => waiting.length };
}

function segment() {
  const s = scriptedIo();
  let pending = 0;
  const errors: string[] = [];
  const seg = new Segment(
    '/spool/journal.lp',
    7,
    { started: () => pending++, finished: () => pending--, onError: (op) => errors.push(op) },
    s.io,
  );
  return { ...s, seg, pending: () => pending, errors };
}

describe('a spool segment syncs one at a time', () => {
  test('seals while a sync runs make one more sync after it, not one each', () => {
    const t = segment();
    t.seg.sync();
    t.seg.sync();
    t.seg.sync();
    t.seg.sync();
    expect(t.calls).toEqual(['fdatasync 7']);
    expect(t.pending()).toBe(1);
    t.finishOne(); // the one after covers the three seals made meanwhile
    expect(t.calls).toEqual(['fdatasync 7', 'fdatasync 7']);
    expect(t.pending()).toBe(1); // never 0 in between: `settled` does not resolve early
    t.finishOne();
    expect(t.calls).toHaveLength(2);
    expect(t.pending()).toBe(0);
  });

  test('retired while a sync runs: one more sync for the last writes, then the close', () => {
    const t = segment();
    t.seg.sync();
    t.seg.retire();
    expect(t.calls).toEqual(['fdatasync 7']);
    t.finishOne();
    t.finishOne();
    expect(t.calls).toEqual(['fdatasync 7', 'fdatasync 7', 'close 7']);
    t.finishOne();
    expect(t.pending()).toBe(0);
    expect(t.seg.fd).toBeNull();
    t.seg.sync(); // closed: nothing more
    expect(t.calls).toHaveLength(3);
  });

  test('retired idle: a sync, then the close', () => {
    const t = segment();
    t.seg.retire();
    t.finishOne();
    t.finishOne();
    expect(t.calls).toEqual(['fdatasync 7', 'close 7']);
    expect(t.pending()).toBe(0);
  });

  test('a failed sync is reported and the next one still runs', () => {
    const t = segment();
    const io = t.io.fdatasync;
    let first = true;
    t.io.fdatasync = (fd, cb) =>
      first ? ((first = false), cb(Object.assign(new Error('EIO'), { code: 'EIO' }))) : io(fd, cb);
    t.seg.sync();
    t.seg.sync();
    expect(t.errors).toEqual(['seal']);
    expect(t.calls).toEqual(['fdatasync 7']);
  });
});
