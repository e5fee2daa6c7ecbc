/**
 * Numeric IK for any serial chain: damped least squares with joint limits (`DlsAttempt`), seeded
 * from the current pose, with seeded random restarts when an attempt stalls, and failure codes
 * (`NUMERIC_IK_CODES`). A solver owns its scratch arrays: build one per chain and reuse it.
 *
 * When the target is not reached the solver tells why (unless `classify` is off):
 *   2  out of reach: not reachable even ignoring the joint limits (or beyond the chain's reach,
 *      or a non-finite target);
 *   9  joint limit: reachable, but only with some joint beyond its limit;
 *   10 orientation unreachable: the position is reachable within the limits, the orientation
 *      (or tool axis) asked for is not, limits or not.
 */
import type { Chain } from './chain-types.ts';
import { DlsAttempt } from './dls.ts';
import { chainFkFrames, createFkFrames } from './fk.ts';
import {
  DEFAULT_NUMERIC_IK_OPTIONS,
  type NumericIkCode,
  type NumericIkOptions,
  type NumericIkResult,
  type NumericTarget,
} from './options.ts';

/** mulberry32: small, fast, seedable; good enough to scatter restarts. */
function nextRandom(state: Uint32Array): number {
  let t = (state[0] = (state[0]! + 0x6d2b79f5) >>> 0);
  t = Math.imul(t ^ (t >>> 15), t | 1);
  t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
  return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
}

function finite(v: ArrayLike<number> | undefined, n: number): boolean {
  if (v === undefined || v.length < n) return false;
  for (let i = 0; i < n; i++) if (!Number.isFinite(v[i])) return false;
  return true;
}

export function createNumericIkResult(chain: Chain): NumericIkResult {
  return {
    code: 0,
    joints: new Float64Array(chain.dof),
    positionError: NaN,
    orientationError: NaN,
    iterations: 0,
    restarts: 0,
  };
}

export class NumericIkSolver {
  readonly options: Readonly<NumericIkOptions>;
  private readonly attempt: DlsAttempt;
  private readonly start: Float64Array;
  private readonly best: Float64Array;
  private readonly rng = new Uint32Array(1);
  private readonly frames;
  private bestErr = Infinity;
  private bestPos = Infinity;
  private bestOri = Infinity;
  private iterations = 0;
  private restarts = 0;

  constructor(
    readonly chain: Chain,
    options: Partial<NumericIkOptions> = {},
  ) {
    this.options = { ...DEFAULT_NUMERIC_IK_OPTIONS, ...options };
    this.attempt = new DlsAttempt(chain, this.options);
    this.start = new Float64Array(chain.dof);
    this.best = new Float64Array(chain.dof);
    this.frames = createFkFrames(chain);
  }

  /** Seeded attempt, then random restarts until one converges. Best attempt kept in `best`. */
  private search(t: NumericTarget, seed: ArrayLike<number>, limited: boolean): boolean {
    const { attempt, chain, start, best } = this;
    for (let i = 0; i < chain.dof; i++) {
      attempt.lo[i] = limited ? chain.lower[i]! : -Infinity;
      attempt.hi[i] = limited ? chain.upper[i]! : Infinity;
    }
    attempt.setTarget(t);
    this.bestErr = Infinity;
    for (let k = 0; k <= this.options.maxRestarts; k++) {
      if (k === 0) start.set(seed as ArrayLike<number>);
      else
        for (let i = 0; i < chain.dof; i++)
          start[i] = chain.lower[i]! + nextRandom(this.rng) * (chain.upper[i]! - chain.lower[i]!);
      const used = attempt.run(t, start);
      if (limited) {
        this.iterations += used;
        this.restarts = k;
      }
      if (attempt.err < this.bestErr) {
        this.bestErr = attempt.err;
        this.bestPos = attempt.posErr;
        this.bestOri = attempt.oriErr;
        best.set(attempt.q);
      }
      if (attempt.converged()) return true;
    }
    return false;
  }

  /**
   * Solve for `target` starting from `seed` (joint values, radians or metres, chain order: the
   * arm's current pose). Never throws; fills and returns `out`.
   */
  solve(
    target: NumericTarget,
    seed: ArrayLike<number>,
    out: NumericIkResult = createNumericIkResult(this.chain),
  ): NumericIkResult {
    const { chain, options: o } = this;
    this.rng[0] = o.seed >>> 0;
    this.iterations = this.restarts = 0;
    const seedOk = finite(seed, chain.dof);
    for (let i = 0; i < chain.dof; i++) {
      const mid = (chain.lower[i]! + chain.upper[i]!) / 2;
      const v = seedOk ? seed[i]! : mid;
      this.start[i] = Math.min(chain.upper[i]!, Math.max(chain.lower[i]!, v));
    }
    const seedQ = Float64Array.from(this.start);
    const p0 = chain.joints[0]!.origin;
    const valid =
      Number.isFinite(target.x) &&
      Number.isFinite(target.y) &&
      Number.isFinite(target.z) &&
      (target.mode === 'position' ||
        (target.mode === 'pose'
          ? finite(target.rotation, 9)
          : finite(target.axis, 3) &&
            Math.hypot(target.axis![0]!, target.axis![1]!, target.axis![2]!) > 1e-12));
    const far =
      !valid ||
      Math.hypot(target.x - p0[12]!, target.y - p0[13]!, target.z - p0[14]!) >
        chain.reachMm + o.positionTolerance;
    if (far) {
      const tip = chainFkFrames(chain, seedQ, this.frames).tip;
      const pos = valid
        ? Math.hypot(target.x - tip[12]!, target.y - tip[13]!, target.z - tip[14]!)
        : NaN;
      return this.finish(out, 2, seedQ, pos, valid && target.mode === 'position' ? 0 : NaN);
    }
    if (this.search(target, seedQ, true))
      return this.finish(out, 0, this.best, this.bestPos, this.bestOri);
    const best = Float64Array.from(this.best);
    const pos = this.bestPos,
      ori = this.bestOri;
    let code: NumericIkCode = 2;
    if (o.classify) {
      if (this.search(target, best, false)) code = 9;
      else if (
        target.mode !== 'position' &&
        this.search({ mode: 'position', x: target.x, y: target.y, z: target.z }, best, true)
      )
        code = 10;
    }
    return this.finish(out, code, best, pos, ori);
  }

  private finish(
    out: NumericIkResult,
    code: NumericIkCode,
    q: ArrayLike<number>,
    pos: number,
    ori: number,
  ): NumericIkResult {
    out.code = code;
    out.joints.set(q);
    out.positionError = pos;
    out.orientationError = ori;
    out.iterations = this.iterations;
    out.restarts = this.restarts;
    return out;
  }
}

/** One-off solve (allocates a solver; reuse a `NumericIkSolver` in a loop). */
export function solveNumericIk(
  chain: Chain,
  target: NumericTarget,
  seed: ArrayLike<number>,
  options: Partial<NumericIkOptions> = {},
): NumericIkResult {
  return new NumericIkSolver(chain, options).solve(target, seed);
}
