/**
 * Ships sealed spool batches to InfluxDB, oldest first, up to `concurrency` requests at once
 * (WRITE_CONCURRENCY: influxd takes concurrent writes faster than one after another). A batch
 * leaves the spool only when InfluxDB accepted it. A failure keeps the batch and drops to one
 * request at a time that backs off exponentially (MIN_RETRY_DELAY_MS doubling up to
 * MAX_RETRY_DELAY_MS) on the oldest batch; the first success brings the others back. A refusal
 * of the data itself (400/413/422) moves the batch to rejected/ and goes on. A 404
 * (database/bucket missing) triggers ensureBucket before the next try.
 */
import { backoffDelay, SYSTEM_CLOCK, type Clock } from '@armtwin/protocol';
import type { InfluxWriter } from './influx.ts';
import { classifyWriteError } from './influx.ts';
import type { Logger, LogOnce } from './log.ts';
import type { Metrics } from './metrics.ts';
import type { Spool, SpoolEntry } from './spool.ts';

export interface ShipperOptions {
  minRetryDelayMs: number;
  maxRetryDelayMs: number;
  /** Requests in flight at once while InfluxDB accepts them (1 while it fails). Default 1. */
  writeConcurrency?: number;
}

/** Back-off before the `failures`-th retry (1: the first): `backoffDelay` from min to max. */
export const retryDelay = (failures: number, o: ShipperOptions): number =>
  backoffDelay(failures - 1, { minMs: o.minRetryDelayMs, maxMs: o.maxRetryDelayMs });

export class Shipper {
  private stopped = false;
  private failures = 0;
  private timer: unknown = null;
  private wake: (() => void) | null = null;
  /** Workers running; each ships the oldest batch nobody else is shipping. */
  private workers = 0;
  private readonly inFlight = new Set<SpoolEntry>();
  private idle: Promise<void> = Promise.resolve();
  private settle: () => void = () => {};
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
    const want = this.failures > 0 ? 1 : Math.max(1, this.opts.writeConcurrency ?? 1);
    while (this.workers < want && this.next()) {
      if (this.workers === 0) this.idle = new Promise((resolve) => (this.settle = resolve));
      this.workers++;
      this.worker().catch((err: Error) => this.log.error({ err }, 'shipper loop failed'));
    }
  }

  /** Stops after the requests in flight; resolves when every worker is idle. */
  async stop(): Promise<void> {
    this.stopped = true;
    this.wake?.();
    await this.idle;
  }

  /** Ships until the spool is empty or `deadlineMs` (clock time) passes; for shutdown. */
  async drain(deadlineMs: number): Promise<boolean> {
    while (this.spool.peek() && this.clock.now() < deadlineMs) {
      if (!(await this.shipOne(this.spool.peek()!))) return false;
    }
    return !this.spool.peek();
  }

  /** The oldest batch no worker is shipping. */
  private next(): SpoolEntry | undefined {
    for (const e of this.spool.queue) if (!this.inFlight.has(e)) return e;
    return undefined;
  }

  private async worker(): Promise<void> {
    try {
      while (!this.stopped) {
        if (this.failures > 0) {
          if (this.workers > 1) return; // failing: one worker probes, oldest batch first
          await this.sleep(retryDelay(this.failures, this.opts));
          if (this.stopped) return;
          this.metrics.retries++;
        }
        const entry = this.next();
        if (!entry) return;
        this.inFlight.add(entry);
        try {
          if ((await this.shipOne(entry)) && this.workers === 1) this.kick(); // back to full speed
        } finally {
          this.inFlight.delete(entry);
        }
      }
    } finally {
      // Here, not in a .finally() of the promise: the next worker must see the count at once.
      if (--this.workers === 0) this.settle();
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

  /** One attempt at a batch; true if it left the spool. */
  private async shipOne(entry: SpoolEntry): Promise<boolean> {
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
