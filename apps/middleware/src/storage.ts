/**
 * The storage pipeline: lines → journal (batch mode) or one request per frame (sync mode) →
 * spool → shipper → InfluxDB. Owns the spool bound: at the bound it pauses intake (`gate()`
 * returns a promise the MQTT edge waits on) and says so loudly.
 */
import type { MiddlewareConfig } from './config.ts';
import { Batcher } from './batcher.ts';
import { classifyWriteError, type InfluxWriter } from './influx.ts';
import type { Logger, LogOnce } from './log.ts';
import type { Metrics } from './metrics.ts';
import type { Clock } from '@armtwin/protocol';
import { Shipper } from './shipper.ts';
import { Spool } from './spool.ts';
import { prepareSpoolTarget } from './spool-target.ts';

export class Storage {
  readonly spool: Spool;
  /** This destination's spool folder (under SPOOL_DIR, see ./spool-target.ts). */
  readonly spoolDir: string;
  private readonly shipper: Shipper;
  private readonly batcher: Batcher;
  private paused: Promise<void> | null = null;
  private resume: (() => void) | null = null;

  constructor(
    private readonly config: MiddlewareConfig,
    private readonly writer: InfluxWriter,
    private readonly metrics: Metrics,
    private readonly log: Logger,
    private readonly once: LogOnce,
    private readonly clock: Clock,
  ) {
    // Each destination its own folder: a batch is only ever written where it was meant to go.
    const target = { url: config.influxUrl, org: config.influxOrg, bucket: config.influxBucket };
    const { dir, adoptedLegacy, others } = prepareSpoolTarget(config.spoolDir, target);
    this.spoolDir = dir;
    if (adoptedLegacy)
      log.warn(
        { dir, bucket: config.influxBucket },
        'a spool from before per-destination folders (no record of its bucket) was adopted by this destination',
      );
    for (const o of others) {
      metrics.spoolOtherPoints += o.points;
      log.warn(
        { ...o.target, files: o.files, points: o.points, dir: o.dir },
        'batches for another InfluxDB destination wait in the spool; they are written only by a middleware configured for it',
      );
    }
    this.spool = new Spool({
      dir,
      maxBytes: config.spoolMaxBytes,
      onDiskError: (op, err) => {
        metrics.diskErrors++;
        once.warn(
          `disk:${op}`,
          { err: err.message, dir },
          `spool ${op} failed: the data stays in memory only`,
        );
      },
    });
    const waiting = this.spool.init();
    if (waiting.files)
      log.info({ ...waiting, dir }, 'spool holds batches from before: replaying them');
    this.shipper = new Shipper(this.spool, writer, metrics, log, once, config, clock);
    this.batcher = new Batcher(
      config,
      () => {
        this.spool.seal();
        this.shipper.kick();
      },
      clock,
    );
    this.shipper.onDrain = () => this.maybeResume();
  }

  /** Creates the database/bucket (when allowed) and starts replaying the spool. */
  start(): void {
    if (this.config.influxCreateBucket) {
      this.writer.ensureBucket().then(
        (what) => {
          this.metrics.influxReachable = true;
          this.log.info(what);
        },
        (err: Error) =>
          this.once.warn(
            'ensure-bucket',
            { reason: err.message },
            'could not check/create the database or bucket (will write anyway)',
          ),
      );
    }
    this.shipper.kick();
  }

  /** Takes one message's lines; in batch mode they are durable at the next `commit`. */
  add(lines: readonly string[]): void {
    if (lines.length === 0) return;
    if (this.config.writeMode === 'sync') {
      for (const line of lines) this.syncWrite(line);
      return;
    }
    this.spool.hold(lines);
    this.batcher.added(lines.length);
    this.checkFull();
  }

  /** Writes the lines taken since the last commit to the journal (one write). */
  commit(): void {
    this.spool.commit();
  }

  /** null, or a promise intake must wait for (spool full). */
  gate(): Promise<void> | null {
    return this.paused;
  }

  /** Seals the open batch and waits until the spool is empty or the timeout passes. */
  async flush(timeoutMs: number): Promise<boolean> {
    this.batcher.flushNow();
    const deadline = this.clock.now() + timeoutMs;
    this.shipper.kick();
    while (this.spool.peek() && this.clock.now() < deadline)
      await new Promise((r) => setTimeout(r, 20));
    return !this.spool.peek();
  }

  /** Seals, writes what it can before the timeout; the rest stays spooled for next time. */
  async stop(timeoutMs: number): Promise<void> {
    this.batcher.flushNow();
    this.batcher.stop();
    await this.shipper.stop();
    const done = await this.shipper.drain(this.clock.now() + timeoutMs);
    if (!done)
      this.log.warn(
        {
          files: this.spool.queue.length,
          points: this.spool.sealedPoints,
          dir: this.spoolDir,
        },
        'stopping with batches still spooled: they are written at the next start',
      );
    await this.spool.settled();
    this.spool.close();
  }

  private checkFull(): void {
    if (this.paused || !this.spool.full) return;
    this.metrics.spoolFull = true;
    this.metrics.spoolFullEvents++;
    this.log.error(
      { bytes: this.spool.bytes, maxBytes: this.config.spoolMaxBytes, dir: this.spoolDir },
      'SPOOL FULL: InfluxDB is not keeping up or is down; MQTT intake is PAUSED (the broker queues the messages) until the spool drains',
    );
    this.batcher.flushNow();
    this.paused = new Promise((resolve) => (this.resume = resolve));
  }

  private maybeResume(): void {
    if (!this.resume || this.spool.full) return;
    this.log.warn({ bytes: this.spool.bytes }, 'spool below its bound again: MQTT intake resumes');
    this.metrics.spoolFull = false;
    this.resume();
    this.resume = null;
    this.paused = null;
  }

  /** WRITE_MODE=sync: one request per frame, as the seed did; a failure goes to the spool. */
  private syncWrite(line: string): void {
    const t0 = this.clock.now();
    this.writer.write(line).then(
      () => {
        this.metrics.writeLatency.observe((this.clock.now() - t0) / 1000);
        this.metrics.batches.ok!++;
        this.metrics.pointsWritten++;
      },
      (raw: unknown) => {
        const err = classifyWriteError(raw);
        this.metrics.batches[err.kind === 'data' ? 'rejected' : 'failed']!++;
        const entry = this.spool.writeSealed(line + '\n', 1);
        if (err.kind === 'data') {
          this.metrics.pointsRejected++;
          this.spool.reject(entry, err.message);
        } else {
          this.once.warn(
            'write-failed',
            { reason: err.message },
            'InfluxDB write failed; spooled for retry',
          );
          this.shipper.kick();
        }
        this.checkFull();
      },
    );
  }
}
