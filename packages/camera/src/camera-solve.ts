/**
 * A camera's pose and vertical field of view from four (or more) image points each matched to a
 * known point of the twin: Levenberg–Marquardt over position, yaw, pitch and fov, minimising the
 * reprojection error, started from the caller's guess and from a ring of cameras around the
 * points (the best fit wins). The camera model is the 3D view's: a pinhole whose up is the arm's
 * +z (no roll), vertical fov, the picture centred; image points are fractions of the picture
 * (0,0 top left, 1,1 bottom right). Pure: no I/O, no three.js; mm in the arm's frame (§4).
 */
import { solveLinear } from '@armtwin/protocol';
import type { CameraPose, Vec3 } from './announcement.ts';

/** One match: a twin point (mm, arm frame) and where it is seen in the picture (fractions). */
export interface PointMatch {
  world: Vec3;
  image: [number, number];
}

export interface CameraGuess {
  pose: CameraPose;
  fovDeg: number;
}

export interface SolveOptions {
  /** Picture width / height. */
  aspect: number;
  /** Where to start as well as the ring (the current pose), optional. */
  guess?: CameraGuess;
  /** LM iterations per start, at most. */
  maxIterations: number;
}

export const DEFAULT_SOLVE_OPTIONS: Omit<SolveOptions, 'aspect'> = { maxIterations: 100 };

export interface SolveResult {
  pose: CameraPose;
  fovDeg: number;
  /** Root-mean-square reprojection error, as a fraction of the picture's height. */
  rms: number;
}

/** LM steps from each start before the most promising `REFINED` go on. */
const ROUGH_ITERATIONS = 15;
const REFINED = 4;
/** A sum of squares this small is an exact fit: no other start can do better. */
const EXACT = 1e-16;

/** Fewest matches the solver takes (6 unknowns, 2 equations a point). */
export const MIN_MATCHES = 4;

/** [x, y, z, yaw, pitch, fovRad]. */
type Params = [number, number, number, number, number, number];

const sub = (a: readonly number[], b: readonly number[]): Vec3 => [
  a[0]! - b[0]!,
  a[1]! - b[1]!,
  a[2]! - b[2]!,
];
const dot = (a: readonly number[], b: readonly number[]) =>
  a[0]! * b[0]! + a[1]! * b[1]! + a[2]! * b[2]!;
const cross = (a: readonly number[], b: readonly number[]): Vec3 => [
  a[1]! * b[2]! - a[2]! * b[1]!,
  a[2]! * b[0]! - a[0]! * b[2]!,
  a[0]! * b[1]! - a[1]! * b[0]!,
];
const norm = (a: readonly number[]) => Math.hypot(a[0]!, a[1]!, a[2]!);
const scale = (a: readonly number[], k: number): Vec3 => [a[0]! * k, a[1]! * k, a[2]! * k];

const UP: Vec3 = [0, 0, 1];
/** Largest |pitch| the solver lets a camera take (straight down has no yaw). */
const MAX_PITCH = (Math.PI / 2) * 0.98;

function direction(yaw: number, pitch: number): Vec3 {
  const c = Math.cos(pitch);
  return [c * Math.cos(yaw), c * Math.sin(yaw), Math.sin(pitch)];
}

/**
 * Where `world` is seen in the picture of a camera at `pose` with vertical `fovDeg` and picture
 * `aspect` (fractions, 0,0 top left), or null when it is not in front of the camera.
 */
export function projectPoint(
  pose: CameraPose,
  fovDeg: number,
  aspect: number,
  world: readonly number[],
): [number, number] | null {
  const d = sub(pose.lookAt, pose.position);
  return projectDir(pose.position, scale(d, 1 / norm(d)), (fovDeg * Math.PI) / 180, aspect, world);
}

function projectDir(
  position: readonly number[],
  d: Vec3,
  fovRad: number,
  aspect: number,
  world: readonly number[],
): [number, number] | null {
  const rRaw = cross(d, UP);
  const rn = norm(rRaw);
  if (rn < 1e-9) return null;
  const r = scale(rRaw, 1 / rn);
  const u = cross(r, d);
  const v = sub(world, position);
  const zc = dot(v, d);
  if (zc <= 1e-6) return null;
  const t = Math.tan(fovRad / 2);
  return [(dot(v, r) / (zc * t * aspect) + 1) / 2, (1 - dot(v, u) / (zc * t)) / 2];
}

/** Residual of a point behind the camera: large, so a step that puts one there is refused. */
const BEHIND = 10;

function residuals(p: Params, matches: readonly PointMatch[], aspect: number, out: number[]): void {
  const d = direction(p[3], p[4]);
  for (let i = 0; i < matches.length; i++) {
    const m = matches[i]!;
    const at = p[5] > 0.01 && p[5] < 3.1 ? projectDir(p, d, p[5], aspect, m.world) : null;
    out[2 * i] = at ? (at[0] - m.image[0]) * aspect : BEHIND;
    out[2 * i + 1] = at ? at[1] - m.image[1] : BEHIND;
  }
}

const sumSq = (r: readonly number[]) => r.reduce((s, x) => s + x * x, 0);

/** Finite-difference steps per parameter (mm, rad, rad). */
const STEPS: Params = [1e-3, 1e-3, 1e-3, 1e-7, 1e-7, 1e-7];

/** Levenberg–Marquardt from `start`; returns the parameters and their sum of squares. */
function levenbergMarquardt(
  start: Params,
  matches: readonly PointMatch[],
  aspect: number,
  maxIterations: number,
): { p: Params; cost: number } {
  const n = 6;
  const mRes = 2 * matches.length;
  let p: Params = [...start];
  const r = new Array<number>(mRes).fill(0);
  const rTry = new Array<number>(mRes).fill(0);
  residuals(p, matches, aspect, r);
  let cost = sumSq(r);
  let lambda = 1e-3;
  const J = Array.from({ length: mRes }, () => new Array<number>(n).fill(0));
  for (let it = 0; it < maxIterations && cost > 1e-24; it++) {
    for (let j = 0; j < n; j++) {
      const q: Params = [...p];
      const h = STEPS[j]!;
      q[j] = q[j]! + h;
      residuals(q, matches, aspect, rTry);
      for (let i = 0; i < mRes; i++) J[i]![j] = (rTry[i]! - r[i]!) / h;
    }
    const JtJ = Array.from({ length: n }, (_, a) =>
      Array.from({ length: n }, (_, b) => J.reduce((s, row) => s + row[a]! * row[b]!, 0)),
    );
    const Jtr = Array.from({ length: n }, (_, a) =>
      J.reduce((s, row, i) => s + row[a]! * r[i]!, 0),
    );
    let improved = false;
    for (let tries = 0; tries < 12 && !improved; tries++) {
      const A = JtJ.map((row, a) => row.map((v, b) => (a === b ? v + lambda * (v || 1e-12) : v)));
      const delta = solveLinear(
        A,
        Jtr.map((v) => -v),
        1e-300,
      );
      if (!delta) {
        lambda *= 10;
        continue;
      }
      const q = p.map((v, j) => v + delta[j]!) as Params;
      q[4] = Math.max(-MAX_PITCH, Math.min(MAX_PITCH, q[4]));
      residuals(q, matches, aspect, rTry);
      const c = sumSq(rTry);
      if (c < cost) {
        const gain = cost - c;
        p = q;
        cost = c;
        for (let i = 0; i < mRes; i++) r[i] = rTry[i]!;
        lambda = Math.max(lambda / 10, 1e-12);
        improved = true;
        if (gain < 1e-16 * (1 + cost)) return { p, cost };
      } else lambda *= 10;
    }
    if (!improved) break;
  }
  return { p, cost };
}

function paramsOf(g: CameraGuess): Params {
  const d = sub(g.pose.lookAt, g.pose.position);
  const len = norm(d);
  return [
    g.pose.position[0],
    g.pose.position[1],
    g.pose.position[2],
    Math.atan2(d[1], d[0]),
    Math.asin(Math.max(-1, Math.min(1, d[2] / len))),
    (g.fovDeg * Math.PI) / 180,
  ];
}

/**
 * The field of view that puts `matches` about where they were clicked, for a camera at
 * `position` looking along `d`: least squares for tan(fov/2) (0 when none is in front).
 */
function matchedFov(
  position: Vec3,
  d: Vec3,
  matches: readonly PointMatch[],
  aspect: number,
): number {
  const r = cross(d, UP);
  const rn = norm(r);
  if (rn < 1e-9) return 0;
  const right = scale(r, 1 / rn);
  const up = cross(right, d);
  let num = 0;
  let den = 0;
  for (const m of matches) {
    const v = sub(m.world, position);
    const z = dot(v, d);
    if (z <= 0) return 0;
    const cx = (2 * m.image[0] - 1) * aspect;
    const cy = 1 - 2 * m.image[1];
    num += (Math.abs(dot(v, right)) / z) * Math.abs(cx) + (Math.abs(dot(v, up)) / z) * Math.abs(cy);
    den += cx * cx + cy * cy;
  }
  const t = den > 0 ? num / den : 0;
  return t > 0 ? 2 * Math.atan(t) : 0;
}

/**
 * Cameras around the points, each looking at their centre, with the field of view that fits
 * the clicks' spread: the ring of starts.
 */
function ringStarts(
  centre: Vec3,
  spread: number,
  matches: readonly PointMatch[],
  aspect: number,
): Params[] {
  const out: Params[] = [];
  for (const distance of [1.2 * spread, 2 * spread, 4 * spread, 8 * spread])
    for (const elevation of [-0.3, 0.25, 0.8])
      for (let k = 0; k < 8; k++) {
        const d = direction((k * Math.PI) / 4 + Math.PI, -elevation);
        const position = sub(centre, scale(d, distance));
        const fov = matchedFov(position, d, matches, aspect);
        if (fov > 0.02 && fov < 3)
          out.push([...position, Math.atan2(d[1], d[0]), Math.asin(d[2]), fov]);
      }
  return out;
}

/**
 * The camera that sees `matches` where they are clicked, or a RangeError's message when there
 * are too few. The `lookAt` returned is on the line of sight, as far away as the points are.
 */
export function solveCamera(
  matches: readonly PointMatch[],
  options: Partial<SolveOptions> & Pick<SolveOptions, 'aspect'>,
): SolveResult {
  const o: SolveOptions = { ...DEFAULT_SOLVE_OPTIONS, ...options };
  if (matches.length < MIN_MATCHES)
    throw new RangeError(`at least ${MIN_MATCHES} points are needed, ${matches.length} given`);
  const centre = scale(
    matches.reduce<Vec3>(
      (s, m) => [s[0] + m.world[0], s[1] + m.world[1], s[2] + m.world[2]],
      [0, 0, 0],
    ),
    1 / matches.length,
  );
  const spread = Math.max(50, ...matches.map((m) => norm(sub(m.world, centre))));
  const starts = [
    ...(o.guess ? [paramsOf(o.guess)] : []),
    ...ringStarts(centre, spread, matches, o.aspect),
  ];
  // A few steps from every start, then the most promising ones to the end.
  const rough: { p: Params; cost: number }[] = [];
  for (const s of starts) {
    const fit = levenbergMarquardt(s, matches, o.aspect, ROUGH_ITERATIONS);
    rough.push(fit);
    if (fit.cost < EXACT) break;
  }
  rough.sort((a, b) => a.cost - b.cost);
  let best = rough[0]!;
  for (const r of rough.slice(0, REFINED)) {
    if (best.cost < EXACT) break;
    const fit = levenbergMarquardt(r.p, matches, o.aspect, o.maxIterations);
    if (fit.cost < best.cost) best = fit;
  }
  const p = best.p;
  const d = direction(p[3], p[4]);
  const position: Vec3 = [p[0], p[1], p[2]];
  const depth = Math.max(100, dot(sub(centre, position), d));
  const lookAt = sub(position, scale(d, -depth));
  return {
    pose: { position, lookAt },
    fovDeg: (p[5] * 180) / Math.PI,
    rms: Math.sqrt(best.cost / matches.length),
  };
}
