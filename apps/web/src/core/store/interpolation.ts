/**
 * The seed's time-based interpolation (Equation 5): t = clamp01((now − start) · α / duration).
 * Each new state report retargets a joint from where it is drawn now to the reported angle,
 * over the expected time to the next report, so a 5 Hz stream still moves smoothly and a 1 kHz
 * stream lands on the latest report every frame (duration ≈ 1 ms). Pure: no clock, no DOM.
 */

export const clamp01 = (v: number): number => (v <= 0 ? 0 : v >= 1 ? 1 : v);

/** Progress in [0, 1]; a non-positive duration means "already there". */
export function progress(now: number, start: number, duration: number, alpha: number): number {
  if (!(duration > 0)) return 1;
  return clamp01(((now - start) * alpha) / duration);
}

/** One joint's motion from `from` to `to`, started at `start` (ms) for `duration` ms. */
export class JointTween {
  from = NaN;
  to = NaN;
  start = 0;
  duration = 0;

  /** Whether a target has ever been set. */
  get known(): boolean {
    return !Number.isNaN(this.to);
  }

  /** The drawn value at `now` (NaN until the first target). */
  valueAt(now: number, alpha: number): number {
    if (Number.isNaN(this.from)) return this.to;
    return this.from + (this.to - this.from) * progress(now, this.start, this.duration, alpha);
  }

  /** Heads for `to` from the value drawn at `now`. The first target is taken at once. */
  retarget(to: number, now: number, duration: number, alpha: number): void {
    this.from = this.known ? this.valueAt(now, alpha) : to;
    this.to = to;
    this.start = now;
    this.duration = duration;
  }

  /** Forgets everything (a new arm, a reconnect). */
  reset(): void {
    this.from = this.to = NaN;
    this.start = this.duration = 0;
  }
}

export interface IntervalEstimatorOptions {
  /** Interval assumed before two reports have arrived, ms (the contract's 50 Hz). */
  initialMs: number;
  /** Shortest interval used, ms. */
  minMs: number;
  /** A gap longer than this is a pause, not a rate, and is not averaged in, ms. */
  maxMs: number;
  /** Weight of the newest interval in the moving average, 0 … 1. */
  smoothing: number;
}

export const DEFAULT_INTERVAL_ESTIMATOR_OPTIONS: IntervalEstimatorOptions = {
  initialMs: 20,
  minMs: 1,
  maxMs: 1000,
  smoothing: 0.2,
};

/** The expected time between state reports: an exponential moving average of arrivals. */
export class IntervalEstimator {
  private readonly opts: IntervalEstimatorOptions;
  private last = NaN;
  private ms: number;

  constructor(opts: Partial<IntervalEstimatorOptions> = {}) {
    this.opts = { ...DEFAULT_INTERVAL_ESTIMATOR_OPTIONS, ...opts };
    this.ms = this.opts.initialMs;
  }

  /** Records an arrival at `now` and returns the expected interval. */
  arrive(now: number): number {
    const dt = now - this.last;
    this.last = now;
    if (dt > 0 && dt <= this.opts.maxMs) {
      const a = this.opts.smoothing;
      this.ms = Math.max(this.opts.minMs, this.ms + a * (dt - this.ms));
    }
    return this.ms;
  }

  get intervalMs(): number {
    return this.ms;
  }

  reset(): void {
    this.last = NaN;
    this.ms = this.opts.initialMs;
  }
}
