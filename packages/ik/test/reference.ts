/**
 * PROTOCOL.md §4 transcribed independently of src/ (plain formulas, demo arm, no early exit):
 * every check that fails for a target, in §4's order, so test vectors can be verified
 * against the formulas rather than against the code under test.
 */
const RAD = Math.PI / 180;
const [L0, L1, L2, L3] = [100, 105, 98, 150];
const TOL = 1e-9;

export interface Reference {
  zp: number;
  d: number;
  cosA: number;
  cosB: number;
  q0: number;
  theta5: number;
  theta4: number;
  theta3: number;
  /** Codes of every failing check, in the order §4 checks them (then 8, the base). */
  fails: number[];
}

const outside = (v: number, lo: number, hi: number) => v < lo - TOL || v > hi + TOL;

export function reference(x: number, y: number, z: number, alpha: number): Reference {
  const q0 = Math.atan2(y, x) / RAD;
  const r = Math.sqrt(x * x + y * y);
  const yp = r - L3 * Math.cos(alpha * RAD);
  const zp = z - L0 - L3 * Math.sin(alpha * RAD);
  const d = Math.sqrt(yp * yp + zp * zp);
  const cosA = (L1 * L1 + d * d - L2 * L2) / (2 * L1 * d);
  const cosB = (L1 * L1 + L2 * L2 - d * d) / (2 * L1 * L2);
  const theta5 = (Math.atan2(zp, yp) + Math.acos(cosA)) / RAD;
  const theta4 = Math.acos(cosB) / RAD - 180;
  const theta3 = alpha - theta5 - theta4;
  const fails: number[] = [];
  if (zp < -L0 - TOL) fails.push(1);
  if (d > L1 + L2 + TOL) fails.push(2);
  if (d === 0 || Math.abs(cosA) > 1 + TOL) fails.push(3);
  if (Math.abs(cosB) > 1 + TOL) fails.push(5);
  // With no triangle the angles are NaN and the limit checks are meaningless.
  if (!Number.isNaN(theta5) && !Number.isNaN(theta4)) {
    if (outside(theta4, -135, 135)) fails.push(4);
    if (outside(theta5, 0, 180)) fails.push(6);
    if (outside(theta3, -90, 90)) fails.push(7);
  }
  if (outside(q0, -135, 135)) fails.push(8);
  return { zp, d, cosA, cosB, q0, theta5, theta4, theta3, fails };
}
