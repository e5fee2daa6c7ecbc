/**
 * Events per second over a sliding window, in fixed buckets (no allocation per event).
 * `now` is any monotonic millisecond clock.
 */
export class RateMeter {
  private readonly counts: Float64Array;
  private readonly bucketMs: number;
  private bucket = NaN; // index (time / bucketMs) of the newest bucket

  constructor(
    readonly windowMs = 1000,
    buckets = 10,
  ) {
    this.counts = new Float64Array(buckets);
    this.bucketMs = windowMs / buckets;
  }

  private advance(now: number): void {
    const b = Math.floor(now / this.bucketMs);
    if (Number.isNaN(this.bucket) || b - this.bucket >= this.counts.length) {
      this.counts.fill(0);
    } else {
      for (let i = this.bucket + 1; i <= b; i++) this.counts[i % this.counts.length] = 0;
    }
    if (Number.isNaN(this.bucket) || b > this.bucket) this.bucket = b;
  }

  add(now: number, n = 1): void {
    this.advance(now);
    this.counts[this.bucket % this.counts.length]! += n;
  }

  /** Events per second in the window ending at `now` (the newest bucket counts as far as it has run). */
  rate(now: number): number {
    this.advance(now);
    let sum = 0;
    for (let i = 0; i < this.counts.length; i++) sum += this.counts[i]!;
    const elapsed = this.windowMs - this.bucketMs + (now - this.bucket * this.bucketMs);
    return (sum * 1000) / elapsed;
  }

  reset(): void {
    this.counts.fill(0);
    this.bucket = NaN;
  }
}
