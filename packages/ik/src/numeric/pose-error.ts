/**
 * The error between the tip and a target, as the 3- or 6-vector the damped least squares
 * step drives to zero: position (mm, target − tip) and orientation as a rotation vector
 * (radians, world frame, the rotation that takes the tip's orientation to the target's).
 */
import type { Mat4 } from './mat4.ts';

/**
 * Rotation vector of R_t · R_cᵀ into `out[3..5]` (the log map); returns its angle. `rt` is the
 * target rotation (3×3 column-major), `tip` the tip transform (4×4 column-major).
 */
export function rotationError(rt: ArrayLike<number>, tip: Mat4, out: Float64Array): number {
  // E = Rt · Rcᵀ: E[r][c] = Σ_k Rt[r][k] · Rc[c][k]. Column-major: Rt[r][k] = rt[k*3+r], Rc[c][k] = tip[k*4+c].
  let e00 = 0,
    e01 = 0,
    e02 = 0,
    e10 = 0,
    e11 = 0,
    e12 = 0,
    e20 = 0,
    e21 = 0,
    e22 = 0;
  for (let k = 0; k < 3; k++) {
    const t0 = rt[k * 3]!,
      t1 = rt[k * 3 + 1]!,
      t2 = rt[k * 3 + 2]!;
    const c0 = tip[k * 4]!,
      c1 = tip[k * 4 + 1]!,
      c2 = tip[k * 4 + 2]!;
    e00 += t0 * c0;
    e01 += t0 * c1;
    e02 += t0 * c2;
    e10 += t1 * c0;
    e11 += t1 * c1;
    e12 += t1 * c2;
    e20 += t2 * c0;
    e21 += t2 * c1;
    e22 += t2 * c2;
  }
  const vx = e21 - e12,
    vy = e02 - e20,
    vz = e10 - e01;
  const cos = Math.max(-1, Math.min(1, (e00 + e11 + e22 - 1) / 2));
  const sin = Math.hypot(vx, vy, vz) / 2;
  const angle = Math.atan2(sin, cos);
  if (angle < 1e-7) {
    out[3] = vx / 2;
    out[4] = vy / 2;
    out[5] = vz / 2;
  } else if (angle < Math.PI - 1e-4) {
    const k = angle / (2 * sin);
    out[3] = vx * k;
    out[4] = vy * k;
    out[5] = vz * k;
  } else {
    // Near 180°: E ≈ 2aaᵀ − I, so the axis is the largest column of (E + I)/2.
    const d0 = (e00 + 1) / 2,
      d1 = (e11 + 1) / 2,
      d2 = (e22 + 1) / 2;
    let ax: number, ay: number, az: number;
    if (d0 >= d1 && d0 >= d2) {
      ax = Math.sqrt(d0);
      ay = (e01 + e10) / 4 / ax;
      az = (e02 + e20) / 4 / ax;
    } else if (d1 >= d2) {
      ay = Math.sqrt(d1);
      ax = (e01 + e10) / 4 / ay;
      az = (e12 + e21) / 4 / ay;
    } else {
      az = Math.sqrt(d2);
      ax = (e02 + e20) / 4 / az;
      ay = (e12 + e21) / 4 / az;
    }
    const n = Math.hypot(ax, ay, az) || 1;
    const sign = ax * vx + ay * vy + az * vz < 0 ? -1 : 1;
    out[3] = (sign * angle * ax) / n;
    out[4] = (sign * angle * ay) / n;
    out[5] = (sign * angle * az) / n;
  }
  return angle;
}

/**
 * Rotation vector turning the tool axis `a` (world, unit) onto `at` (world, unit), into
 * `out[3..5]`; returns the angle between them.
 */
export function axisError(a: ArrayLike<number>, at: ArrayLike<number>, out: Float64Array): number {
  const cx = a[1]! * at[2]! - a[2]! * at[1]!;
  const cy = a[2]! * at[0]! - a[0]! * at[2]!;
  const cz = a[0]! * at[1]! - a[1]! * at[0]!;
  const sin = Math.hypot(cx, cy, cz);
  const cos = a[0]! * at[0]! + a[1]! * at[1]! + a[2]! * at[2]!;
  const angle = Math.atan2(sin, cos);
  if (sin > 1e-12) {
    const k = angle / sin;
    out[3] = cx * k;
    out[4] = cy * k;
    out[5] = cz * k;
  } else if (cos > 0) {
    out[3] = out[4] = out[5] = 0;
  } else {
    // Opposite: turn about any axis perpendicular to a.
    const px = Math.abs(a[0]!) < 0.9 ? 1 : 0,
      py = 1 - px;
    const qx = a[1]! * 0 - a[2]! * py,
      qy = a[2]! * px - a[0]! * 0,
      qz = a[0]! * py - a[1]! * px;
    const n = Math.hypot(qx, qy, qz);
    out[3] = (qx / n) * angle;
    out[4] = (qy / n) * angle;
    out[5] = (qz / n) * angle;
  }
  return angle;
}

/** Solve A·y = b for a symmetric positive definite m×m A (row-major) by Cholesky, in place. */
export function choleskySolve(
  a: Float64Array,
  b: Float64Array,
  y: Float64Array,
  m: number,
): boolean {
  for (let j = 0; j < m; j++) {
    let d = a[j * m + j]!;
    for (let k = 0; k < j; k++) d -= a[j * m + k]! * a[j * m + k]!;
    if (!(d > 0)) return false;
    const l = Math.sqrt(d);
    a[j * m + j] = l;
    for (let i = j + 1; i < m; i++) {
      let s = a[i * m + j]!;
      for (let k = 0; k < j; k++) s -= a[i * m + k]! * a[j * m + k]!;
      a[i * m + j] = s / l;
    }
  }
  for (let i = 0; i < m; i++) {
    let s = b[i]!;
    for (let k = 0; k < i; k++) s -= a[i * m + k]! * y[k]!;
    y[i] = s / a[i * m + i]!;
  }
  for (let i = m - 1; i >= 0; i--) {
    let s = y[i]!;
    for (let k = i + 1; k < m; k++) s -= a[k * m + i]! * y[k]!;
    y[i] = s / a[i * m + i]!;
  }
  return true;
}
