import { describe, expect, it } from 'vitest';
import { ResolutionGovernor } from '../src/scene/ResolutionGovernor.ts';

const feed = (g: ResolutionGovernor, ms: number, n: number) => {
  for (let i = 0; i < n; i++) g.frame(ms);
};

describe('ResolutionGovernor', () => {
  it('keeps full resolution at 60 fps', () => {
    const g = new ResolutionGovernor({ maxRatio: 1 });
    feed(g, 16.7, 240);
    expect(g.ratio).toBe(1);
  });
  it('renders fewer pixels while frames are slow, down to the floor', () => {
    const g = new ResolutionGovernor({ maxRatio: 1, minRatio: 0.35 });
    feed(g, 400, 2); // 800 ms of frames: enough to decide
    expect(g.ratio).toBeCloseTo(0.5, 6);
    feed(g, 400, 4);
    expect(g.ratio).toBe(0.35);
    const g2 = new ResolutionGovernor({ maxRatio: 1 });
    feed(g2, 60, 12); // a little slow: a smaller step
    expect(g2.ratio).toBeGreaterThan(0.6);
    expect(g2.ratio).toBeLessThan(0.85);
  });
  it('climbs back when frames are cheap again, and ignores pauses', () => {
    const g = new ResolutionGovernor({ maxRatio: 1 });
    feed(g, 100, 24);
    const low = g.ratio;
    feed(g, 5000, 100); // a hidden tab: no decision
    expect(g.ratio).toBe(low);
    feed(g, 8, 200);
    expect(g.ratio).toBe(1);
  });
});
