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

describe('FramePacer with a budget (software WebGL in the render worker)', () => {
  /** Ticks every 16 ms with something moving; a frame's cost shows as the time to the next tick. */
  function run(budget: number, costMs: number | ((t: number) => number), untilMs: number) {
    const { renderer, drawn, pacer } = rig({ budget });
    const full = typeof costMs === 'number' ? () => costMs : costMs;
    let busyUntil = 0;
    const draw = (now: number) => {
      drawn.push({ at: now, ratio: renderer.ratio });
      // A frame costs `full` at full resolution, less with fewer pixels (ratio² of them).
      busyUntil = now + Math.max(16, full(now) * (renderer.ratio / 2) ** 2);
    };
    for (let t = 0; t < untilMs;) {
      pacer.step(t, true, draw);
      // The next animation frame comes once the frame drawn is done (a display frame at least).
      t = Math.max(t + 16, Math.ceil(busyUntil / 16) * 16);
    }
    return { renderer, drawn, pacer };
  }

  it('without a budget, draws at every tick while moving', () => {
    const { drawn } = run(1, 0, 1000);
    expect(drawn.length).toBeGreaterThan(60);
  });

  it('keeps the renderer busy at most the budget’s share, and lowers the resolution of costly frames', () => {
    const { drawn, pacer, renderer } = run(0.5, 80, 4000);
    // The busy share: each drawn frame's cost over the whole time.
    const late = drawn.filter((d) => d.at > 2000);
    const busy = late.reduce((s, d) => s + Math.max(16, 80 * (d.ratio / 2) ** 2), 0);
    expect(busy / 2000).toBeLessThanOrEqual(0.55);
    // An 80 ms frame at full resolution is over slowMs: the resolution went down.
    expect(renderer.ratio).toBeLessThan(2);
    expect(pacer.costMs).toBeGreaterThan(0);
    expect(pacer.costMs).toBeLessThanOrEqual(40);
    expect(late.length).toBeGreaterThan(10); // still moving: ≥ 5 frames a second
  });

  it('raises the resolution again, while moving, once frames are cheap', () => {
    const { drawn, renderer } = run(0.5, (t) => (t < 2000 ? 120 : 10), 5000);
    expect(Math.min(...drawn.filter((d) => d.at < 2000).map((d) => d.ratio))).toBeLessThan(1.5);
    expect(renderer.ratio).toBe(2);
  });

  it('a pause (a hidden tab) is not taken for a frame’s cost', () => {
    const { pacer } = rig({ budget: 0.5 });
    const drawn: number[] = [];
    const draw = (now: number) => void drawn.push(now);
    for (let t = 0; t <= 320; t += 32) pacer.step(t, true, draw); // 32 ms frames
    const cost = pacer.costMs;
    expect(cost).toBeCloseTo(32, 0);
    pacer.step(10_000, true, draw); // the next tick came 10 s later: drawn at once
    expect(drawn.at(-1)).toBe(10_000);
    pacer.step(10_032, true, draw);
    expect(pacer.costMs).toBeCloseTo(cost, 6);
    pacer.step(10_064, true, draw); // and the pace is the frames' own again: one every 64 ms
    expect(drawn.slice(-2)).toEqual([10_000, 10_064]);
  });

  it('a frame that waits for the budget is drawn later, not dropped', () => {
    const { renderer, pacer } = rig({ budget: 0.5 });
    const drawn: number[] = [];
    const draw = (now: number) => void drawn.push(now);
    pacer.step(0, true, draw); // drawn
    pacer.step(40, false, draw); // its cost: 40 ms → nothing before 80 ms
    pacer.step(56, true, draw); // moved: waits
    expect(drawn).toEqual([0]);
    pacer.step(72, false, draw); // still waiting, nothing new moved
    pacer.step(88, false, draw); // the budget allows it now: the moved frame is drawn
    expect(drawn).toEqual([0, 88]);
    expect(renderer.ratio).toBe(2);
  });
});
