/**
 * The offset between the arm's `$TIM` clock (epoch ms) and the page's clock (any monotonic ms):
 * the minimum of `arrival − stamp` over a sliding window. A report delayed by the network or
 * by a busy page arrives late and only raises its own difference, so jitter never biases the
 * minimum; what remains in it is the fastest transport time (well under a millisecond on a
 * LAN). `arrival − offset` is then "the arm's time now". Pure: no clock, no allocation.
 */

export interface ClockOffsetOptions {
  /** Width of one bucket of the sliding minimum, ms of page time. */
  bucketMs: number;
  /** Buckets kept: the window is bucketMs × buckets. */
  buckets: number;
  /** A stamp this much older than the newest means the arm's clock was set back: start over, ms. */
  resetBackMs: number;
}

export const DEFAULT_CLOCK_OFFSET_OPTIONS: ClockOffsetOptions = {
  bucketMs: 1000,
  buckets: 10,
  resetBackMs: 1000,
};

export class ClockOffset {
  readonly opts: ClockOffsetOptions;
  private readonly mins: Float64Array;
  private bucket = NaN;
  private newestStamp = NaN;
  private cached = NaN;

  constructor(opts: Partial<ClockOffsetOptions> = {}) {
    this.opts = { ...DEFAULT_CLOCK_OFFSET_OPTIONS, ...opts };
    this.mins = new Float64Array(this.opts.buckets).fill(Infinity);
  }

  /** A stamped report arrived at page time `arrival`. */
  add(arrival: number, stamp: number): void {
    if (!Number.isFinite(arrival) || !Number.isFinite(stamp)) return;
    if (stamp < this.newestStamp - this.opts.resetBackMs) this.reset();
    if (!(stamp <= this.newestStamp)) this.newestStamp = stamp;
    const b = Math.floor(arrival / this.opts.bucketMs);
    if (Number.isNaN(this.bucket)) this.bucket = b;
    // Clear the buckets that went by since the last report (all of them after a long pause).
    for (let k = this.bucket + 1; k <= b && k - this.bucket <= this.opts.buckets; k++)
      this.mins[this.slot(k)] = Infinity;
    if (b > this.bucket) this.bucket = b;
    const slot = this.slot(b);
    const d = arrival - stamp;
    if (d < this.mins[slot]!) this.mins[slot] = d;
    let m = Infinity;
    for (const v of this.mins) if (v < m) m = v;
    this.cached = m;
  }

  private slot(bucket: number): number {
    const n = this.opts.buckets;
    return ((bucket % n) + n) % n;
  }

  /** arrival − stamp at its smallest over the window; NaN before the first stamped report. */
  get offsetMs(): number {
    return Number.isFinite(this.cached) ? this.cached : NaN;
  }

  /** The arm's clock at page time `now` (NaN while the offset is unknown). */
  armTime(now: number): number {
    return now - this.offsetMs;
  }

  reset(): void {
    this.mins.fill(Infinity);
    this.bucket = NaN;
    this.newestStamp = NaN;
    this.cached = NaN;
  }
}
