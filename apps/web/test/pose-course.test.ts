import { describe, expect, it } from 'vitest';
import fc from 'fast-check';
import {
  DEFAULT_POSE_COURSE_OPTIONS,
  PoseCourse,
  courseAfter,
} from '../src/scene/render/PoseCourse.ts';
import { TwinPredictor } from '../src/core/store/TwinPredictor.ts';
import { DrawnPose } from '../src/scene/render/DrawnPose.ts';
import { emptySceneFrame } from '../src/scene/render/SceneFrame.ts';

const EPOCH = 1_700_000_000_000;
const JOINT = { minDeg: -135, maxDeg: 135, maxSpeedDegPerS: 375 };

/** A twin whose page clock is the arm's clock minus EPOCH, joint 0 at rest at 0° from t = 0. */
function twinAtRest(): TwinPredictor {
  const p = new TwinPredictor([JOINT, JOINT]);
  for (let t = 0; t <= 100; t += 20) {
    p.arrive(EPOCH + t, t);
    p.report(0, EPOCH + t, 0);
    p.report(1, EPOCH + t, 10);
  }
  return p;
}

describe('PoseCourse (the render worker poses the predicted twin for its own frame)', () => {
  it('draws the sample before its instant, between course poses after it, and holds at the end', () => {
    const c = new PoseCourse();
    const out = new Float64Array(1);
    c.set(Float64Array.of(0), { at: 1000, stepMs: 10, poses: Float64Array.of(1, 2, 3) });
    c.poseAt(990, out);
    expect(out[0]).toBe(0);
    c.poseAt(1005, out);
    expect(out[0]).toBeCloseTo(0.5, 9);
    c.poseAt(1025, out);
    expect(out[0]).toBeCloseTo(2.5, 9);
    c.poseAt(5000, out);
    expect(out[0]).toBe(3);
    // Without a course (not the predictive twin) the sample is drawn as it is.
    c.set(Float64Array.of(7), null);
    expect(c.poseAt(1025, out)).toBe(true);
    expect(out[0]).toBe(7);
    expect(c.poseAt(1030, out)).toBe(false);
  });

  it('draws a commanded move at the frame’s instant, never past the target', () => {
    fc.assert(
      fc.property(
        fc.double({ min: -100, max: 100, noNaN: true }),
        fc.integer({ min: 0, max: 1500 }),
        fc.integer({ min: 100, max: 1300 }),
        fc.double({ min: 0, max: 200, noNaN: true }),
        (target, dur, sampleAt, drawLag) => {
          const p = twinAtRest();
          p.command(0, target, dur, 100);
          const base = new Float64Array(2);
          p.sample(sampleAt, base);
          const course = courseAfter(p, sampleAt, EPOCH);
          const c = new PoseCourse();
          c.set(base, course);
          const out = new Float64Array(2);
          c.poseAt(EPOCH + sampleAt + drawLag, out);
          // Between where it was and the target, and where the prediction itself has it then
          // (within the corner a step can cut at the end of the move).
          expect(
            Math.min(0, target) - 1e-9 <= out[0]! && out[0]! <= Math.max(0, target) + 1e-9,
          ).toBe(true);
          const truth = new Float64Array(2);
          const { stepMs, steps } = DEFAULT_POSE_COURSE_OPTIONS;
          p.sample(sampleAt + Math.min(drawLag, stepMs * steps), truth);
          // A corner inside one step is cut by at most v·step/4.
          expect(Math.abs(out[0]! - truth[0]!)).toBeLessThanOrEqual(
            (375 / 1000) * (stepMs / 4) + 1e-6,
          );
          expect(out[1]).toBe(10); // the joint not commanded stays where it was reported
        },
      ),
    );
  });

  it('holds a stopped joint: the course after a stop does not move on', () => {
    const p = twinAtRest();
    p.command(0, 90, 1000, 100);
    p.stop(undefined, 300);
    const base = new Float64Array(2);
    p.sample(320, base);
    const c = new PoseCourse();
    c.set(base, courseAfter(p, 320, EPOCH));
    const out = new Float64Array(2);
    c.poseAt(EPOCH + 400, out);
    expect(out[0]).toBeCloseTo(base[0]!, 9);
    expect(base[0]!).toBeLessThan(90 * 0.25);
  });
});

describe('DrawnPose (the worker’s pose of the page’s sample)', () => {
  it('poses the live arm for the tick’s instant plus the learnt tick-to-drawn time', () => {
    const frame = emptySceneFrame();
    const m = new DrawnPose(frame);
    m.take({
      type: 'frame',
      rendered: Float64Array.of(0),
      course: { at: 1000, stepMs: 10, poses: Float64Array.of(1, 2, 3, 4) },
    });
    expect(m.poseAt(1010)).toBe(true);
    expect(frame.rendered[0]).toBeCloseTo(1, 9);
    expect(m.poseAt(1010)).toBe(false);
    // Frames drawn 10 ms after their tick: the pose is taken further on.
    for (let k = 0; k < 100; k++) {
      m.poseAt(1000);
      m.drawn(1010);
    }
    m.poseAt(1010);
    expect(frame.rendered[0]).toBeCloseTo(2, 3);
    // …and says how far past the page's sample that is (the Status panel's lead counts it).
    expect(m.aheadMs).toBeCloseTo(20, 3);
  });

  it('says how far along the course the drawn pose is: 0 before it or without one, its end at most', () => {
    const c = new PoseCourse();
    expect(c.aheadAt(2000)).toBe(0);
    c.set(Float64Array.of(0, 0), {
      at: 1000,
      stepMs: 8,
      poses: Float64Array.of(1, 1, 2, 2, 3, 3),
    });
    expect(c.aheadAt(990)).toBe(0);
    expect(c.aheadAt(1012)).toBe(12);
    expect(c.aheadAt(5000)).toBe(24);
    c.set(Float64Array.of(0, 0), null);
    expect(c.aheadAt(1012)).toBe(0);
  });
});
