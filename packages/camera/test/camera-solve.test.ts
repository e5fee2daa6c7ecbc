import { describe, expect, test } from 'vitest';
import fc from 'fast-check';
import type { CameraPose, Vec3 } from '../src/announcement.ts';
import { projectPoint, solveCamera, type PointMatch } from '../src/camera-solve.ts';

const ASPECT = 4 / 3;

const unit = (a: Vec3, b: Vec3): Vec3 => {
  const d: Vec3 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
  const n = Math.hypot(...d);
  return [d[0] / n, d[1] / n, d[2] / n];
};
const angleDeg = (a: Vec3, b: Vec3) =>
  (Math.acos(Math.min(1, a[0] * b[0] + a[1] * b[1] + a[2] * b[2])) * 180) / Math.PI;

/** The four matches a camera sees, or null when some are off the picture or bunched up. */
function seen(pose: CameraPose, fovDeg: number, points: Vec3[]): PointMatch[] | null {
  const out: PointMatch[] = [];
  for (const world of points) {
    const image = projectPoint(pose, fovDeg, ASPECT, world);
    if (!image || image.some((v) => v < 0.05 || v > 0.95)) return null;
    out.push({ world, image });
  }
  // Spread over the picture: no two within a tenth of it, no three nearly on a line.
  for (let i = 0; i < out.length; i++)
    for (let j = i + 1; j < out.length; j++) {
      const [a, b] = [out[i]!.image, out[j]!.image];
      if (Math.hypot((a[0] - b[0]) * ASPECT, a[1] - b[1]) < 0.1) return null;
      for (let k = j + 1; k < out.length; k++) {
        const c = out[k]!.image;
        const area = Math.abs(
          (b[0] - a[0]) * ASPECT * (c[1] - a[1]) - (c[0] - a[0]) * ASPECT * (b[1] - a[1]),
        );
        if (area < 0.01) return null;
      }
    }
  return out;
}

const coord = (lo: number, hi: number) => fc.double({ min: lo, max: hi, noNaN: true });
const click = fc.tuple(coord(0.08, 0.92), coord(0.08, 0.92), coord(0.6, 1.4));

/**
 * A camera 400–1500 mm from a point near the arm, looking roughly at it, and four points it sees
 * where `clicks` say (picture fractions), each at a depth of 0.6–1.4 times the distance.
 */
const scene = fc
  .record({
    centre: fc.tuple(coord(-250, 250), coord(-250, 250), coord(50, 400)),
    azimuth: coord(-Math.PI, Math.PI),
    elevation: coord(-0.2, 1.1),
    distance: coord(400, 1500),
    aim: fc.tuple(coord(-40, 40), coord(-40, 40), coord(-40, 40)),
    fovDeg: coord(30, 80),
    clicks: fc.tuple(click, click, click, click),
  })
  .map((s) => {
    const c = Math.cos(s.elevation);
    const position: Vec3 = [
      s.centre[0] + s.distance * c * Math.cos(s.azimuth),
      s.centre[1] + s.distance * c * Math.sin(s.azimuth),
      s.centre[2] + s.distance * Math.sin(s.elevation),
    ];
    const lookAt: Vec3 = [s.centre[0] + s.aim[0], s.centre[1] + s.aim[1], s.centre[2] + s.aim[2]];
    const d = unit(position, lookAt);
    const r = unit([0, 0, 0], [d[1], -d[0], 0]);
    const u: Vec3 = [
      r[1] * d[2] - r[2] * d[1],
      r[2] * d[0] - r[0] * d[2],
      r[0] * d[1] - r[1] * d[0],
    ];
    const t = Math.tan((s.fovDeg * Math.PI) / 360);
    const points = s.clicks.map(([x, y, depth]): Vec3 => {
      const z = depth * s.distance;
      const a = (2 * x - 1) * t * ASPECT * z;
      const b = (1 - 2 * y) * t * z;
      return [0, 1, 2].map((i) => position[i]! + z * d[i]! + a * r[i]! + b * u[i]!) as Vec3;
    });
    const depths = s.clicks.map((c) => c[2]);
    return {
      pose: { position, lookAt },
      fovDeg: s.fovDeg,
      points,
      // Points all at one depth cannot tell distance from field of view (a flat picture).
      deep: Math.max(...depths) - Math.min(...depths) >= 0.3,
    };
  });

// Each run solves a camera (milliseconds): a failure is reported as found (seed and path
// replay it) rather than shrunk for minutes.
describe('solveCamera', () => {
  test('recovers a synthetic camera from four exact points, with no guess', () => {
    fc.assert(
      fc.property(scene, ({ pose, fovDeg, points, deep }) => {
        const matches = seen(pose, fovDeg, points);
        fc.pre(matches !== null && deep);
        const got = solveCamera(matches!, { aspect: ASPECT });
        expect(got.rms).toBeLessThan(1e-5);
        expect(Math.hypot(...pose.position.map((v, i) => v - got.pose.position[i]!))).toBeLessThan(
          2,
        );
        expect(
          angleDeg(unit(pose.position, pose.lookAt), unit(got.pose.position, got.pose.lookAt)),
        ).toBeLessThan(0.2);
        expect(Math.abs(got.fovDeg - fovDeg)).toBeLessThan(0.2);
      }),
      { numRuns: 150, endOnFailure: true },
    );
  }, 30_000);

  test('with clicks off by half a pixel (of 480), the pose is still close', () => {
    fc.assert(
      fc.property(
        scene,
        fc.array(coord(-0.5 / 480, 0.5 / 480), { minLength: 8, maxLength: 8 }),
        ({ pose, fovDeg, points, deep }, noise) => {
          const matches = seen(pose, fovDeg, points);
          fc.pre(matches !== null && deep);
          const noisy = matches!.map((m, i) => ({
            world: m.world,
            image: [m.image[0] + noise[2 * i]!, m.image[1] + noise[2 * i + 1]!] as [number, number],
          }));
          const got = solveCamera(noisy, { aspect: ASPECT, guess: { pose, fovDeg } });
          expect(got.rms).toBeLessThan(2 / 480);
          // What an operator sees: each point lands within a couple of pixels of its click.
          for (const m of noisy) {
            const at = projectPoint(got.pose, got.fovDeg, ASPECT, m.world)!;
            expect(Math.hypot((at[0] - m.image[0]) * ASPECT, at[1] - m.image[1])).toBeLessThan(
              3 / 480,
            );
          }
        },
      ),
      { numRuns: 60, endOnFailure: true },
    );
  }, 30_000);

  test('projects the look-at point to the centre, and up the picture along +z', () => {
    const pose: CameraPose = { position: [1000, 0, 300], lookAt: [0, 0, 300] };
    expect(projectPoint(pose, 50, ASPECT, [0, 0, 300])).toEqual([0.5, 0.5]);
    const above = projectPoint(pose, 50, ASPECT, [0, 0, 400])!;
    expect(above[1]).toBeLessThan(0.5);
    // Looking along −x, +y is on the picture's right.
    expect(projectPoint(pose, 50, ASPECT, [0, 100, 300])![0]).toBeGreaterThan(0.5);
    expect(projectPoint(pose, 50, ASPECT, [2000, 0, 300])).toBeNull();
  });

  test('refuses fewer than four points', () => {
    expect(() => solveCamera([], { aspect: ASPECT })).toThrow(RangeError);
  });
});
