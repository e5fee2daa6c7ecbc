import { describe, expect, it } from 'vitest';
import { Takes } from '../src/cameras/index.ts';

const START = [0, 0, 0, 1];
const au = (...units: number[][]) => new Uint8Array(units.flatMap((u) => [...START, ...u]));
const SPS = [0x67, 0x42, 0xc0, 0x1e, 0xda];
const key = au(SPS, [0x68, 0xce], [0x65, 0x88]);
const otherKey = au([0x67, 0x42, 0xc0, 0x1f, 0xda], [0x68, 0xce], [0x65, 0x88]);
const delta = au([0x41, 0x9a]);

describe('takes of a camera feed', () => {
  it('start at a key frame, and stamp each frame from the take’s first', () => {
    const t = new Takes(0);
    expect(t.frame(delta, false, 1000)).toMatchObject({ kind: 'drop', why: 'before-key-frame' });
    expect(t.frame(key, true, 1033)).toMatchObject({ kind: 'write', startTake: true, atMs: 0 });
    expect(t.frame(delta, false, 1066)).toMatchObject({
      kind: 'write',
      startTake: false,
      atMs: 33,
    });
    expect(t.baseMs).toBe(1033);
  });

  it('a frame stamped with its predecessor’s time is written 1 ms after it', () => {
    const t = new Takes(0);
    t.frame(key, true, 1000);
    expect(t.frame(delta, false, 1000)).toMatchObject({ kind: 'write', atMs: 1, bumped: true });
    expect(t.frame(delta, false, 1033)).toMatchObject({ kind: 'write', atMs: 33, bumped: false });
  });

  it('a pause longer than maxGapMs, or new parameter sets, end the take: the next starts at a key frame', () => {
    const t = new Takes(0, { maxGapMs: 500 });
    t.frame(key, true, 1000);
    expect(t.frame(delta, false, 2000)).toMatchObject({ kind: 'drop', endTake: 'gap' });
    expect(t.frame(key, true, 2100)).toMatchObject({ kind: 'write', startTake: true, atMs: 0 });
    expect(t.frame(otherKey, true, 2133)).toMatchObject({
      kind: 'write',
      startTake: true,
      endTake: 'parameters',
      atMs: 0,
    });
    expect(t.end('disconnect')).toBe('disconnect');
    expect(t.end('disconnect')).toBeNull();
  });

  it('frames already on disk (a restarted middleware’s replay) are dropped', () => {
    const t = new Takes(5000);
    expect(t.frame(key, true, 4000)).toMatchObject({ kind: 'drop', why: 'recorded-already' });
    expect(t.frame(delta, false, 5000)).toMatchObject({ kind: 'drop', why: 'recorded-already' });
    expect(t.frame(delta, false, 5033)).toMatchObject({ kind: 'drop', why: 'before-key-frame' });
    expect(t.frame(key, true, 5066)).toMatchObject({ kind: 'write', startTake: true });
  });
});
