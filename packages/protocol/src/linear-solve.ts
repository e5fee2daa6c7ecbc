/**
 * The one dense linear solver of the tree (the thermal model's least squares, the camera
 * solver's Levenberg–Marquardt steps): small n×n systems, so plain Gaussian elimination with
 * partial pivoting and back substitution. Pure.
 */

/**
 * Solves A·x = b (n×n, row-major; neither is changed). Null when A is singular: a pivot no
 * larger than `tiny` in magnitude (default 1e-12).
 */
export function solveLinear(
  a: readonly (readonly number[])[],
  b: readonly number[],
  tiny = 1e-12,
): number[] | null {
  const n = b.length;
  const m = a.map((row, i) => [...row, b[i]!]);
  for (let c = 0; c < n; c++) {
    let piv = c;
    for (let r = c + 1; r < n; r++) if (Math.abs(m[r]![c]!) > Math.abs(m[piv]![c]!)) piv = r;
    if (!(Math.abs(m[piv]![c]!) > tiny)) return null;
    [m[c], m[piv]] = [m[piv]!, m[c]!];
    for (let r = c + 1; r < n; r++) {
      const f = m[r]![c]! / m[c]![c]!;
      for (let k = c; k <= n; k++) m[r]![k]! -= f * m[c]![k]!;
    }
  }
  const x = new Array<number>(n).fill(0);
  for (let r = n - 1; r >= 0; r--) {
    let s = m[r]![n]!;
    for (let k = r + 1; k < n; k++) s -= m[r]![k]! * x[k]!;
    x[r] = s / m[r]![r]!;
  }
  return x;
}
