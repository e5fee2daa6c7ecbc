import { describe, expect, it } from 'vitest';
import { ReplayClock } from '../src/core/replay/ReplayClock.ts';
import { frameIndex, poseAt, slotsFor } from '../src/core/replay/poseAt.ts';
import { ReplayPlayer } from '../src/core/replay/ReplayPlayer.ts';

describe('ReplayClock', () => {
  it('advances by wall time × speed from the tick after play', () => {
    const c = new ReplayClock();
    c.load(10_000, 20_000);
    expect(c.tick(0)).toBe(10_000); // paused
    c.play();
    expect(c.tick(1000)).toBe(10_000); // first tick only starts counting
    expect(c.tick(1500)).toBe(10_500);
    c.setSpeed(4);
    expect(c.tick(2000)).toBe(12_500);
    c.setSpeed(0.25);
    expect(c.tick(3000)).toBe(12_750);
    c.pause();
    expect(c.tick(9000)).toBe(12_750);
    expect(c.fraction).toBeCloseTo(0.275);
  });

  it('stops at the end, and play from the end starts over', () => {
    const c = new ReplayClock();
    c.load(0, 1000);
    c.setSpeed(8);
    c.play();
    c.tick(0);
    expect(c.tick(500)).toBe(1000);
    expect(c.playing).toBe(false);
    c.play();
    expect(c.position).toBe(0);
    expect(c.playing).toBe(true);
  });

  it('seek clamps to the record; an empty record never plays', () => {
    const c = new ReplayClock();
    c.load(100, 200);
    c.seek(50);
    expect(c.position).toBe(100);
    c.seek(1e9);
    expect(c.position).toBe(200);
    c.seek(NaN);
    expect(c.position).toBe(100);
    c.load(5, 5);
    c.play();
    expect(c.playing).toBe(false);
  });
});

describe('poseAt: interpolation between pose frames', () => {
  const rec = {
    times: [1000, 2000, 4000],
    angles: [
      [0, null, 10],
      [10, 20, 10],
      [30, 40, 10], // the API holds a value forward: null only before a servo's first sample
    ],
  };
  const slots = slotsFor(['000', '002', '004'], [0, 1, 2, 3, 4, 5]);

  it('maps ids to servo indices', () => {
    expect(Array.from(slots)).toEqual([0, 2, 4]);
    expect(Array.from(slotsFor(['001', '009', 'x'], [0, 1, 2, 3, 4, 5]))).toEqual([1, -1, -1]);
    // The SO-101's Feetech ids are 1–6: servo 001 is the first servo, 006 the gripper.
    expect(Array.from(slotsFor(['001', '006', '000'], [1, 2, 3, 4, 5, 6]))).toEqual([0, 5, -1]);
  });

  it('finds the frame at or before t', () => {
    expect([999, 1000, 1999, 2000, 3999, 4000, 9999].map((t) => frameIndex(rec.times, t))).toEqual([
      -1, 0, 0, 1, 1, 2, 2,
    ]);
    expect(frameIndex([], 5)).toBe(-1);
  });

  it.each([
    [500, [0, NaN, 10]], // before the first frame: the first pose
    [1000, [0, NaN, 10]],
    [1500, [5, NaN, 10]], // servo 002 unknown until its first sample
    [2000, [10, 20, 10]],
    [3000, [20, 30, 10]], // halfway
    [4000, [30, 40, 10]],
    [5000, [30, 40, 10]],
  ])('t = %i → %j', (t, want) => {
    const out = new Float64Array(6).fill(NaN);
    poseAt(rec, slots, t, out);
    const got = [out[0], out[2], out[4]];
    want.forEach((w, k) =>
      Number.isNaN(w) ? expect(got[k]).toBeNaN() : expect(got[k]).toBeCloseTo(w),
    );
  });

  it('an empty record leaves the pose alone', () => {
    const out = new Float64Array(2).fill(7);
    expect(poseAt({ times: [], angles: [] }, slots, 0, out)).toBe(-1);
    expect(Array.from(out)).toEqual([7, 7]);
  });
});

describe('ReplayPlayer', () => {
  const record = {
    ids: ['000', '002'],
    times: [1000, 3000],
    angles: [
      [0, 0],
      [20, 45],
    ],
    start: 0,
    stop: 4000,
  };

  it('fills the sibling angles as the clock moves; play at 2× reaches the recorded pose', () => {
    const p = new ReplayPlayer([1, 1, 1, 1, 1, 1]);
    p.load(record);
    expect(p.update(0)).toBe(true);
    expect(p.angles[2]).toBe(0);
    expect(p.update(16)).toBe(false); // paused, nothing changed
    p.seek(2000);
    expect(p.update(32)).toBe(true);
    expect(p.angles[0]).toBeCloseTo(10);
    expect(p.angles[2]).toBeCloseTo(22.5);
    expect(p.angles[1]).toBeNaN(); // no record for servo 001
    p.setSpeed(2);
    p.play();
    p.update(100);
    p.update(1100); // +2000 ms of record
    expect(p.clock.playing).toBe(false); // reached the end
    expect(p.angles[2]).toBeCloseTo(45);
  });

  it('applies mounting polarity; close hides the sibling', () => {
    const p = new ReplayPlayer([1, 1, -1, 1, 1, 1]);
    p.load(record);
    p.seek(4000);
    p.update(0);
    expect(p.angles[2]).toBeCloseTo(-45);
    p.close();
    expect(p.active).toBe(false);
    expect(p.update(1)).toBe(true); // one more frame to hide it
    expect(p.update(2)).toBe(false);
  });

  it("a dataset's action is replayed beside its state, with the same polarity", () => {
    const p = new ReplayPlayer([1, 1, -1, 1, 1, 1]);
    p.load({
      ...record,
      action: [
        [2, 5],
        [22, 50],
      ],
    });
    p.seek(2000);
    p.update(0);
    expect(p.actionAngles[0]).toBeCloseTo(12);
    expect(p.actionAngles[2]).toBeCloseTo(-27.5);
    expect(p.angles[2]).toBeCloseTo(-22.5);
    p.load(record); // a record without one: none shown
    p.update(1);
    expect(p.actionAngles[2]).toBeNaN();
  });

  it('configure: sized for another robot (7 servos, track6) whose record replays; the old record closes', () => {
    const p = new ReplayPlayer([1, 1, -1, 1, 1, 1]);
    p.load(record);
    p.update(0);
    p.configure([1, 1, 1, 1, 1, 1, 1]);
    expect(p.record).toBeNull(); // it was the other robot's
    expect(p.angles).toHaveLength(7);
    p.load({
      ids: ['000', '006'],
      times: [0, 1000],
      angles: [
        [-135, 0],
        [0, 90],
      ],
      start: 0,
      stop: 1000,
    });
    p.seek(1000);
    expect(p.update(1)).toBe(true);
    expect(p.angles[0]).toBeCloseTo(0);
    expect(p.angles[6]).toBeCloseTo(90); // servo 006 exists only on the 7-servo robot
    expect(p.angles[2]).toBeNaN();
  });
});
