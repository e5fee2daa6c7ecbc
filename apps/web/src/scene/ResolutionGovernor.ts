/**
 * Dynamic resolution: while the arm moves, frames are rendered back to back, and the time
 * between them is the cost of a frame. When that is slow (software WebGL, a weak laptop), the
 * canvas renders fewer pixels so the twin keeps moving smoothly; when frames are cheap again
 * it climbs back. Pure: fed frame intervals, returns the pixel ratio to use.
 */

export interface ResolutionGovernorOptions {
  /** Highest ratio (the device's pixel ratio, capped). */
  maxRatio: number;
  /** Lowest ratio ever used. */
  minRatio: number;
  /** Average frame interval above which the ratio drops, ms (≈ 22 fps). */
  slowMs: number;
  /** Average frame interval below which the ratio climbs again, ms. */
  fastMs: number;
  /** Frames averaged per decision (fewer when they add up to `windowMs`). */
  window: number;
  /** Longest time averaged per decision, ms, so a very slow start adapts within a second. */
  windowMs: number;
}

export const DEFAULT_RESOLUTION_GOVERNOR_OPTIONS: ResolutionGovernorOptions = {
  maxRatio: 2,
  minRatio: 0.35,
  slowMs: 45,
  fastMs: 14,
  window: 12,
  windowMs: 500,
};

export class ResolutionGovernor {
  readonly opts: ResolutionGovernorOptions;
  ratio: number;
  private sum = 0;
  private count = 0;

  constructor(opts: Partial<ResolutionGovernorOptions> = {}) {
    this.opts = { ...DEFAULT_RESOLUTION_GOVERNOR_OPTIONS, ...opts };
    this.ratio = this.opts.maxRatio;
  }

  /**
   * One interval between two consecutive rendered frames, ms. Returns the new ratio when it
   * changes, else null. Intervals over 1 s (a hidden tab, a pause) are ignored.
   */
  frame(intervalMs: number): number | null {
    if (!(intervalMs > 0 && intervalMs < 1000)) return null;
    this.sum += intervalMs;
    const o = this.opts;
    if (++this.count < o.window && !(this.sum >= o.windowMs && this.count >= 2)) return null;
    const mean = this.sum / this.count;
    this.sum = this.count = 0;
    let next = this.ratio;
    // A frame's cost grows with the pixel count, the square of the ratio: aim under slowMs.
    if (mean > o.slowMs)
      next = Math.max(
        o.minRatio,
        this.ratio * Math.min(0.8, Math.max(0.5, Math.sqrt((0.7 * o.slowMs) / mean))),
      );
    else if (mean < o.fastMs) next = Math.min(o.maxRatio, this.ratio * 1.25);
    if (Math.abs(next - this.ratio) < 1e-3) return null;
    this.ratio = next;
    return next;
  }
}
