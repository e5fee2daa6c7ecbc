/** Options, defaults, targets, results and status codes of the numeric IK (declared once). */

/**
 * Status codes, in the spirit of PROTOCOL.md §4 (0 accepted, 2 out of reach). 9 and 10 are new;
 * 1, 3–8 are the analytic solver's and never come from the numeric one.
 */
export const NUMERIC_IK_CODES = {
  0: 'accepted',
  2: 'out of reach',
  9: 'joint limit',
  10: 'orientation unreachable',
} as const;

export type NumericIkCode = keyof typeof NUMERIC_IK_CODES;

/**
 * What the target constrains. `position`: the tip point only (3 equations). `axis`: the point
 * and the direction of the tip's tool axis (5; e.g. a 5-axis arm's position + pitch, a drill).
 * `pose`: the point and the full orientation (6).
 */
export type TargetMode = 'position' | 'axis' | 'pose';

export interface NumericTarget {
  mode: TargetMode;
  /** Tip position, base frame, mm. */
  x: number;
  y: number;
  z: number;
  /** `pose`: the tip's rotation, 3×3 column-major (three.js `Matrix3.elements` order). */
  rotation?: ArrayLike<number>;
  /** `axis`: the world direction the tool axis should point along (any length > 0). */
  axis?: ArrayLike<number>;
}

export interface NumericIkOptions {
  /** Iterations per attempt (the seeded one and each restart). */
  maxIterations: number;
  /** Random restarts (uniform within the limits) after the seeded attempt fails or stalls. */
  maxRestarts: number;
  /** Converged when the tip is this close to the target, mm. */
  positionTolerance: number;
  /** … and its orientation (or tool axis) within this angle, radians. */
  orientationTolerance: number;
  /**
   * Initial Levenberg–Marquardt damping μ; λ² = μ·mean(diag JJᵀ), so μ is unitless. Divided by
   * 10 after a step that lowers the error, multiplied by 10 after one that does not.
   */
  damping: number;
  /** Smallest μ. */
  dampingMin: number;
  /** An attempt whose μ exceeds this is stuck (a local minimum): restart. */
  dampingMax: number;
  /** Largest change of any joint in one step: radians, or metres for a prismatic joint. */
  maxStep: number;
  /** An attempt is stalled when 10 accepted steps lower the error by less than this fraction. */
  stallRatio: number;
  /** Orientation error weight: 1 rad counts as this fraction of the chain's length. */
  orientationWeight: number;
  /** The tip frame's tool axis (its own coordinates) for `axis` targets. */
  toolAxis: readonly [number, number, number];
  /** Seed of the restarts' pseudo-random joint values (same input → same answer). */
  seed: number;
  /**
   * When the target is not reached, run the extra solves that tell 2, 9 and 10 apart (without
   * limits; position only). Off: every failure is 2.
   */
  classify: boolean;
}

export const DEFAULT_NUMERIC_IK_OPTIONS: Readonly<NumericIkOptions> = {
  maxIterations: 60,
  maxRestarts: 30,
  positionTolerance: 0.01,
  orientationTolerance: 1e-4,
  damping: 1e-3,
  dampingMin: 1e-9,
  dampingMax: 1e4,
  maxStep: 0.35,
  stallRatio: 1e-3,
  orientationWeight: 0.2,
  toolAxis: [0, 0, 1],
  seed: 1,
  classify: true,
};

export interface NumericIkResult {
  code: NumericIkCode;
  /**
   * Joint values (radians or metres, chain order), always within the limits: the solution when
   * code is 0, otherwise the best attempt (closest to the target).
   */
  joints: Float64Array;
  /** Remaining distance to the target, mm (NaN for a non-finite target). */
  positionError: number;
  /** Remaining orientation (or tool-axis) error, radians; 0 for `position` targets; NaN when not evaluated (a target beyond reach). */
  orientationError: number;
  /** Iterations used, over every attempt of the limited solve. */
  iterations: number;
  /** Random restarts used. */
  restarts: number;
}

/**
 * The target a tip transform `m` (4×4 column-major, mm) describes, in `mode`: its position,
 * rotation (`pose`) or the world direction of `toolAxis` (`axis`).
 */
export function targetFromTransform(
  m: ArrayLike<number>,
  mode: TargetMode,
  toolAxis: readonly [number, number, number] = DEFAULT_NUMERIC_IK_OPTIONS.toolAxis,
): NumericTarget {
  const t: NumericTarget = { mode, x: m[12]!, y: m[13]!, z: m[14]! };
  if (mode === 'pose')
    t.rotation = [m[0]!, m[1]!, m[2]!, m[4]!, m[5]!, m[6]!, m[8]!, m[9]!, m[10]!];
  if (mode === 'axis') {
    const [ax, ay, az] = toolAxis;
    t.axis = [0, 1, 2].map((r) => m[r]! * ax + m[4 + r]! * ay + m[8 + r]! * az);
  }
  return t;
}
