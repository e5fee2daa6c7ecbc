import { describe, expect, it } from 'vitest';
import { FramePacer } from '../src/scene/FramePacer.ts';

/** A renderer stand-in that records its pixel ratio, and a draw that records what it drew at. */
function rig(opts: ConstructorParameters<typeof FramePacer>[2] = {}) {
  const renderer = {
    ratio: 0,
    getPixelRatio: () => renderer.ratio,
    setPixelRatio: (r: number) => (renderer.ratio = r),
  };
  const drawn: { at: number; ratio: number }[] = [];
  const pacer = new FramePacer(renderer, 2, opts);
  const draw = (now: number) => drawn.push({ at: now, ratio: renderer.ratio });
  return { renderer, drawn, pacer, draw };
}

describe('FramePacer', () => {
  it('draws only when something moved, and the warm-up frames regardless', () => {
    const { drawn, pacer, draw } = rig({ warmupFrames: 2 });
    for (let t = 0; t < 5; t++) pacer.step(t * 16, false, draw);
    expect(drawn.map((d) => d.at)).toEqual([0, 16]);
    pacer.step(100, true, draw);
    expect(drawn.at(-1)?.at).toBe(100);
  });

  it('lowers the resolution while moving frames are slow, then draws once at full resolution when idle', () => {
    const { renderer, drawn, pacer, draw } = rig({ refineAfterMs: 300 });
    let t = 0;
    for (let i = 0; i < 20; i++) pacer.step((t += 200), true, draw);
    expect(renderer.ratio).toBeLessThan(2);
    const moving = drawn.length;
    pacer.step(t + 100, false, draw); // not idle long enough yet
    expect(drawn.length).toBe(moving);
    pacer.step(t + 400, false, draw);
    expect(drawn.length).toBe(moving + 1);
    expect(drawn.at(-1)?.ratio).toBe(2);
    pacer.step(t + 800, false, draw); // once only
    expect(drawn.length).toBe(moving + 1);
  });
});
