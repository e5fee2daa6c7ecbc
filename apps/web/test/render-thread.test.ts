/** Where the 3D view is drawn (`?render=`), and what the page sends its render worker. */
import { describe, expect, it } from 'vitest';
import { Writable } from 'node:stream';
import { chooseRenderThread } from '../src/core/config/renderThread.ts';
import { sameValues, targetDiffers } from '../src/scene/render/frameDiff.ts';
import type { TargetState } from '../src/scene/render/messages.ts';
import { flushNow } from '../src/core/link/flushNow.ts';

describe('chooseRenderThread', () => {
  it('draws in a worker by default where possible, on the main thread when asked', () => {
    const paced = { note: '', pace: true };
    expect(chooseRenderThread('', true)).toEqual({ thread: 'worker', ...paced });
    expect(chooseRenderThread('?render=worker', true)).toEqual({ thread: 'worker', ...paced });
    expect(chooseRenderThread('?render=main', true)).toEqual({ thread: 'main', ...paced });
    expect(chooseRenderThread('?render=nonsense', true).thread).toBe('worker');
    expect(chooseRenderThread('', false).thread).toBe('main');
    expect(chooseRenderThread('?render=worker&render=main', true).thread).toBe('main');
  });

  it('falls back to the main thread, saying why, where there is no OffscreenCanvas', () => {
    const c = chooseRenderThread('?render=worker', false);
    expect(c.thread).toBe('main');
    expect(c.note).toMatch(/OffscreenCanvas/);
    expect(chooseRenderThread('', false, { defaultThread: 'worker' }).thread).toBe('main');
  });

  it('paces software WebGL unless `?frames=full` asks for every frame', () => {
    expect(chooseRenderThread('?frames=full', true).pace).toBe(false);
    expect(chooseRenderThread('?frames=full&render=main', false).pace).toBe(false);
    expect(chooseRenderThread('?frames=paced', true).pace).toBe(true);
    expect(chooseRenderThread('?frames=full&frames=x', true).pace).toBe(true);
  });

  it('a default of main is taken when the query says nothing', () => {
    expect(chooseRenderThread('', true, { defaultThread: 'main' }).thread).toBe('main');
    expect(chooseRenderThread('?render=worker', true, { defaultThread: 'main' }).thread).toBe(
      'worker',
    );
  });

  it('a default of worker is taken when the query says nothing', () => {
    expect(chooseRenderThread('', true, { defaultThread: 'worker' }).thread).toBe('worker');
    expect(chooseRenderThread('?render=main', true, { defaultThread: 'worker' }).thread).toBe(
      'main',
    );
  });
});

describe('frame diffs', () => {
  it('sameValues counts NaN equal to NaN and tells lengths and values apart', () => {
    expect(sameValues([1, NaN, 3], Float64Array.of(1, NaN, 3))).toBe(true);
    expect(sameValues([1, 2], [1, 2, 3])).toBe(false);
    expect(sameValues([1, NaN], [1, 0])).toBe(false);
    expect(sameValues([0.5], [0.25])).toBe(false);
  });

  const target = (over: Partial<TargetState> = {}): TargetState => ({
    active: true,
    x: 200,
    y: 0,
    z: 150,
    code: 0,
    angles: new Float64Array(4).fill(NaN),
    hitJoint: '',
    ghostEnabled: true,
    refused: false,
    refusedAngles: new Float64Array(4).fill(NaN),
    refusedJoint: '',
    ...over,
  });

  it('targetDiffers sees any field change, and nothing when all are the same', () => {
    expect(targetDiffers(target(), null)).toBe(true);
    expect(targetDiffers(target(), target())).toBe(false);
    expect(targetDiffers(target({ x: 201 }), target())).toBe(true);
    expect(targetDiffers(target({ ghostEnabled: false }), target())).toBe(true);
    expect(targetDiffers(target({ angles: Float64Array.of(1, NaN, NaN, NaN) }), target())).toBe(
      true,
    );
    expect(targetDiffers(target({ refusedJoint: 'elbow' }), target())).toBe(true);
  });
});

describe('flushNow', () => {
  it('puts a corked write on the transport at once, inside the call', () => {
    const written: string[] = [];
    const stream = new Writable({
      write(chunk: Buffer, _enc, cb) {
        written.push(chunk.toString());
        cb();
      },
    });
    // As mqtt-packet writes a packet: corked, uncorked on the next tick.
    stream.cork();
    stream.write('#255PDST!');
    expect(written).toEqual([]);
    flushNow({ stream });
    expect(written).toEqual(['#255PDST!']);
    expect(stream.writableCorked).toBe(0);
    stream.uncork(); // the later nextTick uncork: nothing left, no error
    expect(written).toEqual(['#255PDST!']);
  });

  it('does nothing without a stream', () => {
    expect(() => flushNow(null)).not.toThrow();
    expect(() => flushNow({})).not.toThrow();
  });
});
