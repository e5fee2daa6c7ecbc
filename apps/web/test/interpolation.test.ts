import { describe, expect, it } from 'vitest';
import {
  IntervalEstimator,
  JointTween,
  clamp01,
  progress,
} from '../src/core/store/interpolation.ts';

describe('progress: t = clamp01((now − start)·α / duration)', () => {
  it('is 0 at the start, 1 at the end, linear between, clamped outside', () => {
    expect(progress(100, 100, 200, 1)).toBe(0);
    expect(progress(150, 100, 200, 1)).toBe(0.25);
    expect(progress(300, 100, 200, 1)).toBe(1);
    expect(progress(900, 100, 200, 1)).toBe(1);
    expect(progress(50, 100, 200, 1)).toBe(0);
  });
  it('scales with α', () => {
    expect(progress(150, 100, 200, 2)).toBe(0.5);
    expect(progress(150, 100, 200, 0.5)).toBe(0.125);
  });
  it('treats a zero or negative duration as arrived', () => {
    expect(progress(100, 100, 0, 1)).toBe(1);
    expect(clamp01(-3)).toBe(0);
  });
});

describe('JointTween', () => {
  it('takes the first target at once, then moves linearly to the next', () => {
    const j = new JointTween();
    expect(Number.isNaN(j.valueAt(0, 1))).toBe(true);
    j.retarget(10, 0, 200, 1);
    expect(j.valueAt(0, 1)).toBe(10);
    j.retarget(30, 200, 200, 1);
    expect(j.valueAt(200, 1)).toBe(10);
    expect(j.valueAt(300, 1)).toBe(20);
    expect(j.valueAt(400, 1)).toBe(30);
    expect(j.valueAt(10_000, 1)).toBe(30);
  });

  it('at 5 Hz the drawn angle moves every frame in small, even steps (smooth, no jumps)', () => {
    const j = new JointTween();
    let target = 0;
    j.retarget(target, 0, 200, 1);
    const steps: number[] = [];
    let last = j.valueAt(0, 1);
    for (let t = 0; t <= 2000; t += 1000 / 60) {
      // a report every 200 ms, 3° further each time
      if (Math.floor(t / 200) > Math.floor((t - 1000 / 60) / 200))
        j.retarget((target += 3), t, 200, 1);
      const v = j.valueAt(t, 1);
      steps.push(v - last);
      last = v;
    }
    expect(Math.max(...steps)).toBeLessThanOrEqual(1.1 * (3 / 12)); // 3° over ~12 frames
    expect(steps.slice(20).every((s) => s > 0)).toBe(true); // never stalls between reports
  });

  it('at 1 kHz the drawn angle is the latest report each frame (never falls behind)', () => {
    const j = new JointTween();
    const est = new IntervalEstimator();
    let drawn = 0;
    for (let ms = 0; ms <= 1000; ms++) {
      j.retarget(ms / 10, ms, est.arrive(ms), 1);
      if (ms % 16 === 0) drawn = j.valueAt(ms + 1, 1);
    }
    expect(est.intervalMs).toBeCloseTo(1, 1);
    expect(drawn).toBeCloseTo(99.2, 1); // the report at 992 ms, 1 ms later
  });

  it('retargets from where it is drawn now, so a new report never makes it jump', () => {
    const j = new JointTween();
    j.retarget(0, 0, 100, 1);
    j.retarget(100, 0, 100, 1);
    const at50 = j.valueAt(50, 1);
    j.retarget(-100, 50, 100, 1);
    expect(j.valueAt(50, 1)).toBe(at50);
  });
});

describe('IntervalEstimator', () => {
  it('converges on the report interval and ignores pauses', () => {
    const e = new IntervalEstimator();
    for (let t = 0; t < 10_000; t += 200) e.arrive(t);
    expect(e.intervalMs).toBeCloseTo(200, 0);
    e.arrive(10_000 + 3000); // a 3 s pause is not a rate
    expect(e.intervalMs).toBeCloseTo(200, 0);
  });
});
