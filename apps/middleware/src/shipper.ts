/**
 * Ships sealed spool batches to InfluxDB, oldest first, one request at a time. A failure
 * keeps the batch and backs off exponentially (MIN_RETRY_DELAY_MS doubling up to
 * MAX_RETRY_DELAY_MS) for every later batch too, so order is kept; a refusal of the data
 * itself (400/413/422) moves the batch to rejected/ and goes on. A 404 (database/bucket
 * missing) triggers ensureBucket before the next try.
 */
import type { InfluxWriter } from './influx.ts';
import { classifyWriteError } from './influx.ts';
import type { Logger, LogOnce } from './log.ts';
import type { Metrics } from './metrics.ts';
import type { Spool } from './spool.ts';

export interface ShipperOptions {
  minRetryDelayMs: number;
  maxRetryDelayMs: number;
}

export interface Clock {
  now(): number;
  setTimeout(fn: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
}

export const SYSTEM_CLOCK: Clock = {
  now: () => performance.now(),
  setTimeout: (fn, ms) => setTimeout(fn, ms),
  clearTimeout: (h) => clearTimeout(h as NodeJS.Timeout),
};

/** Back-off before the `failures`-th retry: min · 2^(failures−1), capped. */
export const retryDelay = (failures: number, o: ShipperOptions): number =>
  Math.min(o.maxRetryDelayMs, o.minRetryDelayMs * 2 ** Math.min(30, Math.max(0, failures - 1)));

export class Shipper {
  private running = false;
  private stopped = false;
  private failures = 0;
  private timer: unknown = null;
  private wake: (() => void) | null = null;
  private idle: Promise<void> = Promise.resolve();
  /** Called after every batch leaves the spool (frees space: resumes a paused intake). */
  onDrain: () => void = () => {};

  constructor(
    private readonly spool: Spool,
    private readonly writer: InfluxWriter,
    private readonly metrics: Metrics,
    private readonly log: Logger,
    private readonly once: LogOnce,
    private readonly opts: ShipperOptions,
    private readonly clock: Clock = SYSTEM_CLOCK,
  ) {}

  /** There is something new in the spool (or a retry may go now). */
  kick(): void {
    if (this.stopped) return;
    if (this.wake && this.failures === 0) this.wake();
    if (!this.running) {
      this.running = true;
      this.idle = this.loop()
        .catch((err: Error) => this.log.error({ err }, 'shipper loop failed'))
        .finally(() => {
          this.running = false;
        });
    }
  }

  /** Stops after the request in flight; resolves when the loop is idle. */
  async stop(): Promise<void> {
    this.stopped = true;
    this.wake?.();
    await this.idle;
  }

  /** Ships until the spool is empty or `deadlineMs` (clock time) passes; for shutdown. */
  async drain(deadlineMs: number): Promise<boolean> {
    while (this.spool.peek() && this.clock.now() < deadlineMs) {
      if (!(await this.shipOne())) return false;
    }
    return !this.spool.peek();
  }

  private async loop(): Promise<void> {
    while (!this.stopped && this.spool.peek()) {
      if (this.failures > 0) {
        await this.sleep(retryDelay(this.failures, this.opts));
        if (this.stopped) return;
        this.metrics.retries++;
      }
      await this.shipOne();
    }
  }

  private sleep(ms: number): Promise<void> {
    return new Promise((resolve) => {
      this.wake = () => {
        this.clock.clearTimeout(this.timer);
        this.wake = null;
        resolve();
      };
      this.timer = this.clock.setTimeout(() => this.wake?.(), ms);
    });
  }

  /** One attempt at the oldest batch; true if it left the spool. */
  private async shipOne(): Promise<boolean> {
    const entry = this.spool.peek();
    if (!entry) return true;
    const body = this.spool.read(entry);
    const t0 = this.clock.now();
    try {
      await this.writer.write(body);
      this.metrics.writeLatency.observe((this.clock.now() - t0) / 1000);
      this.metrics.batches.ok!++;
      this.metrics.pointsWritten += entry.points;
      this.metrics.influxReachable = true;
      if (this.failures > 0) {
        this.log.info(
          { after: this.failures, spoolFiles: this.spool.queue.length - 1 },
          'InfluxDB writes again; replaying the spool',
        );
        this.once.reset('write-failed');
      }
      this.failures = 0;
      this.spool.remove(entry);
      this.onDrain();
      return true;
    } catch (raw) {
      const err = classifyWriteError(raw);
      if (err.kind === 'data') {
        const where = this.spool.reject(entry, err.message);
        this.metrics.batches.rejected!++;
        this.metrics.pointsRejected += entry.points;
        this.log.error(
          { points: entry.points, file: where, reason: err.message },
          'InfluxDB refused a batch as bad data; kept in rejected/',
        );
        this.onDrain();
        return true;
      }
      this.metrics.batches.failed!++;
      this.failures++;
      if (err.kind === 'network') this.metrics.influxReachable = false;
      this.once.warn(
        'write-failed',
        { reason: err.message, status: err.status, spoolFiles: this.spool.queue.length },
        'InfluxDB write failed; batches stay in the spool and are retried',
        50,
      );
      if (err.kind === 'not-found') {
        await this.writer.ensureBucket().then(
          (what) => this.log.info(what),
          (e: Error) =>
            this.once.warn(
              'ensure-bucket',
              { reason: e.message },
              'could not create the database/bucket',
            ),
        );
      }
      return false;
    }
  }
}
