/**
 * Teaching by showing: a recording of k straight joint moves with stops between them becomes
 * k + 1 waypoints whatever the sampling and noise; the plan those waypoints run (the real
 * planner, linear and timed) reproduces every recorded sample within the tolerance; reversals
 * are kept; bad recordings get a clear refusal.
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { servoFromPwm } from '@armtwin/robot';
import { US_PER_DEG } from '@armtwin/protocol';
import {
  DEFAULT_TEACH_OPTIONS,
  planJoint,
  samplePlan,
  teachFromRecording,
  tipPose,
  topSpeed,
  type MotionRobot,
  type Plan,
  type TaughtWaypoint,
} from '../src/index.ts';
import { home, loadRobot } from './fixtures.ts';

const robots = { armtwin5: loadRobot('armtwin5'), track6: loadRobot('track6') };
const TOL = DEFAULT_TEACH_OPTIONS;
/** Sensor noise (°) that moves the tip well inside `tipMm` (track6's reach is 1.5 m and more). */
const NOISE_DEG = { armtwin5: 0.2, track6: 0.03 };

interface Synthetic {
  times: number[];
  pwm: number[][];
}

/**
 * Stops at `poses` (held `dwellMs[k]`, 0 = pass through), straight moves between them at
 * `speed` × each servo's limit, sampled every `sampleMs` with uniform noise of ±`noiseUs`.
 */
function synthetic(
  robot: MotionRobot,
  poses: readonly (readonly number[])[],
  dwellMs: readonly number[],
  sampleMs: number,
  speed: number,
  noise: () => number = () => 0,
): Synthetic {
  const keys: { t: number; q: readonly number[] }[] = [];
  let t = 0;
  poses.forEach((q, k) => {
    if (k > 0) {
      const prev = poses[k - 1]!;
      const T = Math.max(...q.map((p, i) => Math.abs(p - prev[i]!) / topSpeed(robot, i, speed)));
      t += Math.max(T, sampleMs);
    }
    keys.push({ t, q });
    t += dwellMs[k] ?? 0;
    keys.push({ t, q });
  });
  const at = (time: number): number[] => {
    const j = keys.findIndex((k) => k.t > time);
    if (j <= 0) return [...keys[j < 0 ? keys.length - 1 : 0]!.q];
    const a = keys[j - 1]!;
    const b = keys[j]!;
    const u = (time - a.t) / (b.t - a.t);
    return a.q.map((p, i) => p + (b.q[i]! - p) * u);
  };
  const times: number[] = [];
  const pwm: number[][] = [];
  for (let s = 0; s <= t + 1e-9; s += sampleMs) {
    times.push(s);
    pwm.push(at(s).map((p) => p + noise()));
  }
  return { times, pwm };
}

/** The plan the Plan panel runs for taught waypoints (linear, timed), from the first one. */
function taughtPlan(robot: MotionRobot, w: readonly TaughtWaypoint[]): Plan {
  const rest = w.slice(1);
  return planJoint(
    robot,
    w[0]!.pwm,
    rest.map((x) => x.pwm),
    { profile: 'linear', speed: 0.3 },
    rest.map((x) => ({ durationMs: x.durationMs, holdMs: x.holdMs })),
  );
}

/** Worst joint (°/mm) and tip (mm) error of the executed plan against the recording. */
function executedError(robot: MotionRobot, rec: Synthetic, w: readonly TaughtWaypoint[]) {
  const plan = taughtPlan(robot, w);
  let joint = 0;
  let tip = 0;
  rec.times.forEach((t, k) => {
    const p = samplePlan(plan, t - w[0]!.t);
    const q = rec.pwm[k]!;
    robot.profile.servos.forEach((s, i) => {
      joint = Math.max(joint, Math.abs(servoFromPwm(s, p[i]!) - servoFromPwm(s, q[i]!)));
    });
    const a = tipPose(robot, p);
    const b = tipPose(robot, q);
    tip = Math.max(tip, Math.hypot(a.x - b.x, a.y - b.y, a.z - b.z));
  });
  return { joint, tip };
}

/** A pose near home: each servo within ±`spanUs` of it, inside the limits. */
const nearHome = (robot: MotionRobot, spanUs = 300) =>
  fc.tuple(
    ...robot.table.map((s) =>
      fc.double({
        min: Math.max(s.minPwm, s.homePwm - spanUs),
        max: Math.min(s.maxPwm, s.homePwm + spanUs),
        noNaN: true,
      }),
    ),
  );

describe.each(Object.entries(robots))('teaching on %s', (name, robot) => {
  const noiseDeg = NOISE_DEG[name as keyof typeof NOISE_DEG];
  const h = home(robot);
  const poses = [
    h,
    h.map((p, i) => p + (i % 2 === 0 ? 200 : -150)),
    h.map((p, i) => p + (i % 3 === 0 ? -180 : 120)),
    h.map((p, i) => p + 60 * (i - 2)),
  ];

  it.each([20, 50, 200])(
    'three moves with stops, sampled every %i ms, give four waypoints within tolerance',
    (sampleMs) => {
      const rec = synthetic(robot, poses, [1000, 800, 1200, 1000], sampleMs, 0.4);
      const r = teachFromRecording(robot, rec);
      if (!r.ok) throw new Error(r.error);
      expect(r.samples).toBe(rec.times.length);
      expect(r.waypoints).toHaveLength(4);
      r.waypoints.forEach((w, k) =>
        w.pwm.forEach((p, i) => expect(Math.abs(p - poses[k]![i]!)).toBeLessThan(0.5)),
      );
      expect(r.error.maxDeg).toBeLessThan(0.5);
      expect(r.error.maxTipMm).toBeLessThan(TOL.tipMm / 2);
      // The middle stops are held (to a sample); the ends are where the plan starts and ends.
      const holds = r.waypoints.map((w) => w.holdMs);
      [0, 800, 1200, 0].forEach((hold, k) =>
        expect(Math.abs(holds[k]! - hold)).toBeLessThanOrEqual(sampleMs),
      );
      const e = executedError(robot, rec, r.waypoints);
      expect(e.joint).toBeLessThan(0.5);
      expect(e.tip).toBeLessThan(TOL.tipMm / 2);
    },
  );

  it('noise inside the tolerance adds no waypoint', () => {
    let seed = 7;
    const rand = () => ((seed = (seed * 1103515245 + 12345) % 2 ** 31) / 2 ** 31) * 2 - 1;
    const rec = synthetic(
      robot,
      poses,
      [1000, 800, 1200, 1000],
      50,
      0.4,
      () => rand() * noiseDeg * US_PER_DEG,
    );
    const r = teachFromRecording(robot, rec);
    if (!r.ok) throw new Error(r.error);
    expect(r.waypoints).toHaveLength(4);
    expect(r.error.maxDeg).toBeLessThanOrEqual(TOL.jointDeg);
    expect(r.error.maxTipMm).toBeLessThanOrEqual(TOL.tipMm);
  });

  it('keeps a reversal without a stop as a waypoint', () => {
    const out = h.map((p, i) => (i === 1 ? p + 300 : p));
    const rec = synthetic(robot, [h, out, h], [500, 0, 500], 20, 0.4);
    const r = teachFromRecording(robot, rec);
    if (!r.ok) throw new Error(r.error);
    // The turn falls between two samples: one waypoint at it, or one on each side.
    expect(r.waypoints.length).toBeGreaterThanOrEqual(3);
    expect(r.waypoints.length).toBeLessThanOrEqual(4);
    const turn = Math.max(...r.waypoints.map((w) => w.pwm[1]!));
    expect(Math.abs(turn - out[1]!) / US_PER_DEG).toBeLessThanOrEqual(TOL.jointDeg);
  });

  it('fast-check: the taught plan never strays beyond the tolerance from the recording', () => {
    let refused = 0;
    fc.assert(
      fc.property(
        fc.array(nearHome(robot), { minLength: 2, maxLength: 5 }),
        fc.array(fc.constantFrom(0, 150, 400, 1500), { minLength: 5, maxLength: 5 }),
        fc.constantFrom(20, 50, 100, 200),
        fc.double({ min: 0.05, max: 0.4, noNaN: true }),
        fc.double({ min: 0, max: noiseDeg, noNaN: true }),
        fc.integer({ min: 1, max: 2 ** 30 }),
        (ps, dwell, sampleMs, speed, noiseDeg, s0) => {
          let seed = s0;
          const rand = () => ((seed = (seed * 1103515245 + 12345) % 2 ** 31) / 2 ** 31) * 2 - 1;
          const rec = synthetic(
            robot,
            ps,
            dwell,
            sampleMs,
            speed,
            () => rand() * noiseDeg * US_PER_DEG,
          );
          const r = teachFromRecording(robot, rec);
          if (!r.ok) {
            refused++;
            expect(r.error).toMatch(/did not move|needs \d+ waypoints/);
            return;
          }
          expect(r.error.maxDeg).toBeLessThanOrEqual(TOL.jointDeg + 1e-9);
          expect(r.error.maxMm).toBeLessThanOrEqual(TOL.jointMm + 1e-9);
          expect(r.error.maxTipMm).toBeLessThanOrEqual(TOL.tipMm + 1e-9);
          // The planner samples the plan every stepMs: its rounding is far below a micron.
          const e = executedError(robot, rec, r.waypoints);
          expect(e.joint).toBeLessThanOrEqual(TOL.jointDeg + 1e-3);
          expect(e.tip).toBeLessThanOrEqual(TOL.tipMm + 1e-3);
        },
      ),
      {
        numRuns: 60,
        // A failure is reported as found, not shrunk: shrinking runs the whole teach and plan
        // per try, and a fresh clone's unit stage had spent 17 minutes on it when stopped.
        endOnFailure: true,
        // Found by a CI run: the last moving sample before a stop was out of tolerance of it, and
        // the stop's arrival was put at that sample's own time (a jump in no time, 1e-9 mm over).
        // Then by a fresh clone: the stop's departure extrapolated 2e-12 ms before the next
        // sample, a waypoint there: the planner took the servos' time for that segment and ran the
        // rest of the plan late (4.6° from the recording; now never faster than the servos).
        examples: [
          // armtwin5's poses (outside track6's ranges).
          ...(name === 'armtwin5'
            ? [
                [
                  [
                    [
                      1200.0000000000014, 1650.3561032916143, 1200.000000000001, 1200.0000000000023,
                      1233.8823844333667, 1672.3593034014282,
                    ],
                    [
                      1200.0000000000032, 1718.8893713825241, 1200.000000000002, 1203.5969104628768,
                      1200.0000000000025, 1671.858023488094,
                    ],
                    [
                      1520.6388468761668, 1760.8304296146239, 1438.0198182802244,
                      1473.6952996106838, 1446.4505961132654, 1799.9999999999966,
                    ],
                    [
                      1340.3204626487047, 1544.2797384944045, 1558.216093411261, 1634.5576969474425,
                      1383.5374646117518, 1799.9999999999968,
                    ],
                    [
                      1373.180788763697, 1429.665021121331, 1299.1244791420006, 1424.9641746722255,
                      1377.2463805234127, 1579.7146757491976,
                    ],
                  ],
                  [1500, 0, 400, 1500, 1500],
                  200,
                  0.2241113523624718,
                  0,
                  1073741811,
                ],
              ]
            : []),
          [
            [
              [1200, 1200, 1200, 1200, 1200, 1500],
              [1200, 1200, 1573.1725835000268, 1328.2179646525412, 1200, 1500],
              [1722.1529495898271, 1200, 1200, 1200, 1200, 1500],
              [1599.1696190907371, 1200, 1200, 1799.9999999999982, 1200, 1500],
              [1200, 1200, 1200, 1200, 1200, 1500],
            ],
            [150, 0, 400, 0, 0],
            20,
            0.05,
            0.1999999999999914,
            8,
          ],
        ],
      },
    );
    expect(refused).toBeLessThan(10);
  });
});

describe('teaching refuses what it cannot use', () => {
  const robot = robots.armtwin5;
  const h = home(robot);

  it('names too few samples and a still arm', () => {
    const one = teachFromRecording(robot, { times: [0], pwm: [h] });
    expect(one).toMatchObject({ ok: false, error: expect.stringMatching(/at least 2/) });
    const still = teachFromRecording(robot, { times: [0, 500, 1000], pwm: [h, h, h] });
    expect(still).toMatchObject({ ok: false, error: expect.stringMatching(/did not move/) });
  });

  it('leaves a servo the recording never saw (NaN), and fills gaps in the others', () => {
    const to = h.map((p) => p + 100);
    const rec = synthetic(robot, [h, to], [500, 500], 50, 0.4);
    const pwm = rec.pwm.map((row, k) => row.map((p, i) => (i === 5 ? null : k === 3 ? null : p)));
    const r = teachFromRecording(robot, { times: rec.times, pwm });
    if (!r.ok) throw new Error(r.error);
    expect(r.waypoints).toHaveLength(2);
    expect(r.waypoints.every((w) => Number.isNaN(w.pwm[5]))).toBe(true);
  });

  it('refuses more waypoints than allowed, saying how many were needed', () => {
    const zigzag = Array.from({ length: 12 }, (_, k) =>
      h.map((p, i) => (i === 0 ? p + (k % 2) * 300 : p)),
    );
    const rec = synthetic(robot, zigzag, new Array<number>(12).fill(400), 20, 0.4);
    const r = teachFromRecording(robot, rec, { maxWaypoints: 5 });
    expect(r).toMatchObject({
      ok: false,
      error: expect.stringMatching(/needs 12 waypoints.*at most 5/),
    });
  });
});

describe('timed joint targets', () => {
  const robot = robots.armtwin5;
  const h = home(robot);
  const to = h.map((p, i) => (i === 0 ? p + 100 : p));

  it('take their duration and hold, at most as fast as the servo allows', () => {
    const plan = planJoint(robot, h, [to, h], { profile: 'linear' }, [
      { durationMs: 2000, holdMs: 500 },
      { durationMs: 1 },
    ]);
    expect(plan.targetTimes[0]).toBeCloseTo(2000, 6);
    expect(samplePlan(plan, 1000)[0]).toBeCloseTo(h[0]! + 50, 6);
    expect(samplePlan(plan, 2400)[0]).toBeCloseTo(to[0]!, 6);
    // 100 µs at 375°/s (4167 µs/s) take 24 ms at the limit: 1 ms is stretched to that.
    expect(plan.durationMs - 2500).toBeCloseTo(100 / topSpeed(robot, 0, 1), 6);
  });
});
