/** Least-squares line fits for the soak's per-minute series. Pure: no clock, no I/O. */

export interface LineFit {
  /** Change of y per unit of x. */
  slope: number;
  intercept: number;
  /** How many (x, y) pairs with finite values went into the fit. */
  n: number;
}

/** The ordinary least-squares line through the finite (x, y) pairs; NaN slope below 2 points. */
export function leastSquares(xs: ArrayLike<number>, ys: ArrayLike<number>): LineFit {
  let n = 0;
  let sx = 0;
  let sy = 0;
  for (let i = 0; i < Math.min(xs.length, ys.length); i++) {
    const x = xs[i]!;
    const y = ys[i]!;
    if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
    n++;
    sx += x;
    sy += y;
  }
  if (n < 2) return { slope: NaN, intercept: NaN, n };
  const mx = sx / n;
  const my = sy / n;
  let sxx = 0;
  let sxy = 0;
  for (let i = 0; i < Math.min(xs.length, ys.length); i++) {
    const x = xs[i]!;
    const y = ys[i]!;
    if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
    sxx += (x - mx) ** 2;
    sxy += (x - mx) * (y - my);
  }
  if (sxx === 0) return { slope: NaN, intercept: NaN, n };
  const slope = sxy / sxx;
  return { slope, intercept: my - slope * mx, n };
}

/** The fit over the samples whose x is at least `fromX` (the soak skips its warm-up minutes). */
export function slopeFrom(xs: readonly number[], ys: readonly number[], fromX: number): LineFit {
  const keep = xs.map((x, i) => (x >= fromX ? i : -1)).filter((i) => i >= 0);
  return leastSquares(
    keep.map((i) => xs[i]!),
    keep.map((i) => ys[i]!),
  );
}
