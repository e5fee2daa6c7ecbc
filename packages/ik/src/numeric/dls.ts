/**
 * One damped least squares (Levenberg–Marquardt) attempt with joint limits, on preallocated
 * arrays. Each step solves Δq = J_Fᵀ (J_F J_Fᵀ + λ²I)⁻¹ e, where J_F is the Jacobian with the
 * columns of joints pinned at a limit (and pushed further out) removed, scales Δq so no joint
 * moves more than `maxStep`, and clamps q + Δq into the limits. A step that lowers the error is
 * taken and λ shrinks; one that does not is refused and λ grows.
 */
import type { Chain } from './chain-types.ts';
import { chainFkFrames, createFkFrames, type FkFrames } from './fk.ts';
import type { NumericIkOptions, NumericTarget } from './options.ts';
import { axisError, choleskySolve, rotationError } from './pose-error.ts';

export class DlsAttempt {
  readonly frames: FkFrames;
  readonly q: Float64Array;
  /** Limits in force (the chain's, or ±Infinity for the limit-free check). */
  readonly lo: Float64Array;
  readonly hi: Float64Array;
  err = Infinity;
  posErr = Infinity;
  oriErr = Infinity;
  private readonly n: number;
  private readonly qTry: Float64Array;
  private readonly dq: Float64Array;
  private readonly free: Uint8Array;
  private readonly jac: Float64Array;
  private readonly a = new Float64Array(36);
  private readonly y = new Float64Array(6);
  private readonly e = new Float64Array(6);
  private readonly eTry = new Float64Array(6);
  private readonly axisNow = new Float64Array(3);
  private readonly axisTarget = new Float64Array(3);
  private m = 3;
  private w = 1;

  constructor(
    private readonly chain: Chain,
    private readonly o: NumericIkOptions,
  ) {
    const n = (this.n = chain.dof);
    this.frames = createFkFrames(chain);
    this.q = new Float64Array(n);
    this.lo = Float64Array.from(chain.lower);
    this.hi = Float64Array.from(chain.upper);
    this.qTry = new Float64Array(n);
    this.dq = new Float64Array(n);
    this.free = new Uint8Array(n);
    this.jac = new Float64Array(6 * n);
  }

  /** Set the target's rows and weights; call before `run`. */
  setTarget(t: NumericTarget): void {
    this.m = t.mode === 'position' ? 3 : 6;
    this.w = this.o.orientationWeight * this.chain.lengthMm;
    if (t.mode === 'axis' && t.axis) {
      const n = Math.hypot(t.axis[0]!, t.axis[1]!, t.axis[2]!);
      for (let i = 0; i < 3; i++) this.axisTarget[i] = t.axis[i]! / n;
    }
  }

  /** Evaluate the error at `q` into `e` (orientation rows weighted): returns the weighted squared norm; sets pos/ori errors. */
  private evaluate(q: Float64Array, t: NumericTarget, e: Float64Array): number {
    const tip = chainFkFrames(this.chain, q, this.frames).tip;
    e[0] = t.x - tip[12]!;
    e[1] = t.y - tip[13]!;
    e[2] = t.z - tip[14]!;
    const pos = Math.hypot(e[0], e[1], e[2]);
    let ori = 0;
    if (t.mode === 'pose' && t.rotation) ori = rotationError(t.rotation, tip, e);
    else if (t.mode === 'axis') {
      const [ax, ay, az] = this.o.toolAxis,
        an = this.axisNow;
      for (let r = 0; r < 3; r++) an[r] = tip[r]! * ax + tip[4 + r]! * ay + tip[8 + r]! * az;
      ori = axisError(an, this.axisTarget, e);
    }
    if (this.m === 6) for (let r = 3; r < 6; r++) e[r] = e[r]! * this.w;
    this.posErr = pos;
    this.oriErr = ori;
    return pos * pos + (this.m === 6 ? this.w * this.w * ori * ori : 0);
  }

  converged(): boolean {
    return this.posErr <= this.o.positionTolerance && this.oriErr <= this.o.orientationTolerance;
  }

  /** Fill the Jacobian (m×n, row-major, orientation rows weighted) from the current frames. */
  private jacobian(t: NumericTarget): void {
    const { n, jac, w } = this;
    const { axes, points, tip } = this.frames;
    const px = tip[12]!,
      py = tip[13]!,
      pz = tip[14]!;
    const an = this.axisNow;
    for (let i = 0; i < n; i++) {
      const ax = axes[3 * i]!,
        ay = axes[3 * i + 1]!,
        az = axes[3 * i + 2]!;
      if (this.chain.joints[i]!.type === 'prismatic') {
        jac[i] = ax * 1000;
        jac[n + i] = ay * 1000;
        jac[2 * n + i] = az * 1000;
        jac[3 * n + i] = jac[4 * n + i] = jac[5 * n + i] = 0;
        continue;
      }
      const dx = px - points[3 * i]!,
        dy = py - points[3 * i + 1]!,
        dz = pz - points[3 * i + 2]!;
      jac[i] = ay * dz - az * dy;
      jac[n + i] = az * dx - ax * dz;
      jac[2 * n + i] = ax * dy - ay * dx;
      let rx = ax,
        ry = ay,
        rz = az;
      if (t.mode === 'axis') {
        // Turning about the tool axis itself does not move it: project that part out.
        const d = ax * an[0]! + ay * an[1]! + az * an[2]!;
        rx -= d * an[0]!;
        ry -= d * an[1]!;
        rz -= d * an[2]!;
      }
      jac[3 * n + i] = w * rx;
      jac[4 * n + i] = w * ry;
      jac[5 * n + i] = w * rz;
    }
  }

  /** Δq for damping `mu`, honouring the limits; false when no joint can move. */
  private step(mu: number): boolean {
    const { n, m, jac, a, y, dq, free, q, lo, hi } = this;
    const e = this.e;
    free.fill(1);
    for (let pass = 0; pass <= n; pass++) {
      let trace = 0;
      for (let r = 0; r < m; r++)
        for (let c = 0; c <= r; c++) {
          let s = 0;
          for (let i = 0; i < n; i++) if (free[i]) s += jac[r * n + i]! * jac[c * n + i]!;
          a[r * m + c] = a[c * m + r] = s;
          if (r === c) trace += s;
        }
      const lambda2 = mu * (trace / m) + 1e-12;
      for (let r = 0; r < m; r++) a[r * m + r] = a[r * m + r]! + lambda2;
      if (!choleskySolve(a, e, y, m)) return false;
      let big = 0;
      for (let i = 0; i < n; i++) {
        let s = 0;
        if (free[i]) for (let r = 0; r < m; r++) s += jac[r * n + i]! * y[r]!;
        dq[i] = s;
        big = Math.max(big, Math.abs(s));
      }
      if (big > this.o.maxStep) for (let i = 0; i < n; i++) dq[i] = (dq[i]! * this.o.maxStep) / big;
      let pinned = false;
      for (let i = 0; i < n; i++) {
        if (!free[i]) continue;
        if ((q[i]! <= lo[i]! + 1e-12 && dq[i]! < 0) || (q[i]! >= hi[i]! - 1e-12 && dq[i]! > 0)) {
          free[i] = 0;
          pinned = true;
        }
      }
      if (!pinned) return big > 0;
    }
    return false;
  }

  /** Run one attempt from `start` (clamped into the limits). Returns the iterations used. */
  run(t: NumericTarget, start: ArrayLike<number>): number {
    const { n, q, qTry, dq, lo, hi, o } = this;
    for (let i = 0; i < n; i++) q[i] = Math.min(hi[i]!, Math.max(lo[i]!, start[i]!));
    this.err = this.evaluate(q, t, this.e);
    let mu = o.damping;
    let windowErr = this.err;
    let accepted = 0;
    let it = 0;
    let pos = this.posErr,
      ori = this.oriErr;
    while (it < o.maxIterations && !this.converged()) {
      it++;
      this.jacobian(t);
      if (!this.step(mu)) break;
      for (let i = 0; i < n; i++) qTry[i] = Math.min(hi[i]!, Math.max(lo[i]!, q[i]! + dq[i]!));
      const errTry = this.evaluate(qTry, t, this.eTry);
      if (errTry < this.err) {
        q.set(qTry);
        this.e.set(this.eTry);
        this.err = errTry;
        pos = this.posErr;
        ori = this.oriErr;
        mu = Math.max(mu / 10, o.dampingMin);
        if (++accepted % 10 === 0) {
          if (this.err > windowErr * (1 - o.stallRatio)) break;
          windowErr = this.err;
        }
      } else {
        // Refused: back to q's frames and errors, more damping.
        this.evaluate(q, t, this.e);
        this.posErr = pos;
        this.oriErr = ori;
        mu *= 10;
        if (mu > o.dampingMax) break;
      }
    }
    return it;
  }
}
