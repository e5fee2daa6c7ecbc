/**
 * 4×4 rigid transforms in column-major `Float64Array(16)`s (the layout of three.js's
 * `Matrix4.elements`, so `new Matrix4().fromArray(m)` reads one): element (row r, column c) is
 * `m[c * 4 + r]`, the translation is `m[12], m[13], m[14]`. Every function writes into an `out`
 * the caller owns, so a solver's inner loop allocates nothing.
 */

export type Mat4 = Float64Array;

export function createMat4(): Mat4 {
  return mat4Identity(new Float64Array(16));
}

export function mat4Identity(out: Mat4): Mat4 {
  out.fill(0);
  out[0] = out[5] = out[10] = out[15] = 1;
  return out;
}

/**
 * `out = a · b`. Row by row, so `out` may be `a` (t ← t·m in place); it must not be `b`.
 */
export function mat4Multiply(out: Mat4, a: Mat4, b: Mat4): Mat4 {
  for (let r = 0; r < 4; r++) {
    const a0 = a[r]!,
      a1 = a[4 + r]!,
      a2 = a[8 + r]!,
      a3 = a[12 + r]!;
    for (let c = 0; c < 4; c++) {
      const k = c * 4;
      out[k + r] = a0 * b[k]! + a1 * b[k + 1]! + a2 * b[k + 2]! + a3 * b[k + 3]!;
    }
  }
  return out;
}

export function mat4Copy(out: Mat4, a: ArrayLike<number>): Mat4 {
  for (let i = 0; i < 16; i++) out[i] = a[i]!;
  return out;
}

/**
 * The URDF `<origin xyz rpy>` transform: translation (x, y, z), rotation
 * Rz(yaw)·Ry(pitch)·Rx(roll) (fixed axes: roll about x first, then pitch about y, then yaw about z).
 */
export function mat4FromXyzRpy(
  out: Mat4,
  x: number,
  y: number,
  z: number,
  roll: number,
  pitch: number,
  yaw: number,
): Mat4 {
  const cr = Math.cos(roll),
    sr = Math.sin(roll);
  const cp = Math.cos(pitch),
    sp = Math.sin(pitch);
  const cy = Math.cos(yaw),
    sy = Math.sin(yaw);
  out[0] = cy * cp;
  out[1] = sy * cp;
  out[2] = -sp;
  out[3] = 0;
  out[4] = cy * sp * sr - sy * cr;
  out[5] = sy * sp * sr + cy * cr;
  out[6] = cp * sr;
  out[7] = 0;
  out[8] = cy * sp * cr + sy * sr;
  out[9] = sy * sp * cr - cy * sr;
  out[10] = cp * cr;
  out[11] = 0;
  out[12] = x;
  out[13] = y;
  out[14] = z;
  out[15] = 1;
  return out;
}

/** `t ← t · Rot(axis, angle)` in place; `axis` is a unit vector in t's frame (Rodrigues). */
export function mat4RotateAxisInPlace(
  t: Mat4,
  ax: number,
  ay: number,
  az: number,
  angle: number,
): Mat4 {
  const c = Math.cos(angle),
    s = Math.sin(angle),
    v = 1 - c;
  // Columns of the rotation R (column-major).
  const r00 = c + ax * ax * v,
    r10 = ay * ax * v + az * s,
    r20 = az * ax * v - ay * s;
  const r01 = ax * ay * v - az * s,
    r11 = c + ay * ay * v,
    r21 = az * ay * v + ax * s;
  const r02 = ax * az * v + ay * s,
    r12 = ay * az * v - ax * s,
    r22 = c + az * az * v;
  for (let r = 0; r < 3; r++) {
    const a0 = t[r]!,
      a1 = t[4 + r]!,
      a2 = t[8 + r]!;
    t[r] = a0 * r00 + a1 * r10 + a2 * r20;
    t[4 + r] = a0 * r01 + a1 * r11 + a2 * r21;
    t[8 + r] = a0 * r02 + a1 * r12 + a2 * r22;
  }
  return t;
}

/** `t ← t · Trans(d · axis)` in place; `axis` in t's frame. */
export function mat4TranslateAxisInPlace(
  t: Mat4,
  ax: number,
  ay: number,
  az: number,
  d: number,
): Mat4 {
  const x = ax * d,
    y = ay * d,
    z = az * d;
  for (let r = 0; r < 3; r++) t[12 + r] = t[12 + r]! + t[r]! * x + t[4 + r]! * y + t[8 + r]! * z;
  return t;
}

/** Roll, pitch, yaw (URDF convention, radians) of a transform's rotation, into `out`. */
export function rpyFromMat4(
  m: ArrayLike<number>,
  out: [number, number, number] = [0, 0, 0],
): [number, number, number] {
  out[1] = Math.asin(Math.max(-1, Math.min(1, -m[2]!)));
  if (Math.abs(m[2]!) < 1 - 1e-12) {
    out[0] = Math.atan2(m[6]!, m[10]!);
    out[2] = Math.atan2(m[1]!, m[0]!);
  } else {
    out[0] = 0;
    out[2] = Math.atan2(-m[4]!, m[5]!);
  }
  return out;
}
