/**
 * When to seal the open batch: at `batchSize` points, or `flushIntervalMs` after the first
 * point of the batch, whichever comes first. Holds no data itself: it counts, and calls
 * `flush` (which seals the spool's open batch and wakes the shipper).
 */
import { SYSTEM_CLOCK, type Clock } from '@armtwin/protocol';

export interface BatcherOptions {
  /** Points per batch (BATCH_SIZE). */
  batchSize: number;
  /** Longest wait of a point before its batch is sealed (FLUSH_INTERVAL_MS). */
  flushIntervalMs: number;
}

export class Batcher {
  private points = 0;
  private timer: unknown = null;

  constructor(
    private readonly opts: BatcherOptions,
    private readonly flush: () => void,
    private readonly clock: Clock = SYSTEM_CLOCK,
  ) {}

  /** `n` points were appended to the open batch. */
  added(n: number): void {
    if (n <= 0) return;
    this.points += n;
    if (this.points >= this.opts.batchSize) this.flushNow();
    else if (this.timer === null)
      this.timer = this.clock.setTimeout(() => this.flushNow(), this.opts.flushIntervalMs);
  }

  get pending(): number {
    return this.points;
  }

  flushNow(): void {
    if (this.timer !== null) this.clock.clearTimeout(this.timer);
    this.timer = null;
    if (this.points === 0) return;
    this.points = 0;
    this.flush();
  }

  stop(): void {
    if (this.timer !== null) this.clock.clearTimeout(this.timer);
    this.timer = null;
  }
}
