/**
 * The half-duplex bus line as the gateway uses it (pure): a queue of requests, one on the line
 * at a time. A request that expects answers waits for them (the bus client's `feed`) or for its
 * time-out (`replyTimeoutMs` at the line's baud rate, then `expire`); one that does not (sync
 * writes) is written and the next one follows at once. Goals can be dropped from the queue and
 * urgent requests put at its head, so a stop beats anything queued. After a time-out the line
 * is drained for `BUS_DRAIN_MS` (bytes dropped, nothing sent, the client's reader started
 * afresh), so a late answer is never taken for the next request's.
 */
import {
  createBusClient,
  replyTimeoutMs,
  type BusClient,
  type BusProtocol,
  type BusResult,
} from '@armtwin/servo-bus';
import { busCalibrations, type BusJoint } from './bus-servos.ts';
import type { ConfigWrite } from './bus-writes.ts';

/** Quiet time after a time-out, ms: late answers still on their way are dropped. */
export const BUS_DRAIN_MS = 40;

export type BusJobTag = 'ping' | 'positions' | 'health' | 'goal' | 'hold' | 'torque' | 'config';

interface Job {
  tag: BusJobTag;
  make(client: BusClient): Uint8Array;
  /** Present when answers are awaited. */
  then?: (result: BusResult | undefined) => void;
}

export interface BusLineIo {
  write(data: Uint8Array): boolean;
  setTimeout(fn: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
  onFirst(kind: string, message: string): void;
}

export interface BusLineCounters {
  requests: number;
  writes: number;
  /** Waits that ended with servos missing. */
  timeouts: number;
  /** Requests that could not be written (line down) or could not be encoded. */
  failed: number;
  /** Goals dropped from the queue by a stop. */
  droppedGoals: number;
  /** Bytes dropped while draining after a time-out. */
  drainedBytes: number;
}

type Positions = Extract<BusResult, { kind: 'positions' }>;
type Health = Extract<BusResult, { kind: 'health' }>;

export class BusLine {
  readonly counters: BusLineCounters = {
    requests: 0,
    writes: 0,
    timeouts: 0,
    failed: 0,
    droppedGoals: 0,
    drainedBytes: 0,
  };
  ready = false;
  private client!: BusClient;
  private queue: Job[] = [];
  private current: Job | undefined;
  private timer: unknown;
  private pumping = false;
  private draining: unknown;
  /** The client's calibrations are out of date. */
  private stale = false;

  constructor(
    private readonly protocol: BusProtocol,
    private readonly joints: readonly BusJoint[],
    private readonly baudRate: number,
    private readonly io: BusLineIo,
  ) {
    this.reset();
  }

  /** Forgets everything queued and awaited (the line closed or reopened). */
  reset(): void {
    this.io.clearTimeout(this.timer);
    this.timer = undefined;
    this.queue = [];
    this.current = undefined;
    this.ready = false;
    this.io.clearTimeout(this.draining);
    this.draining = undefined;
    this.newClient();
  }

  /**
   * The joints' calibration changed (`BusGatewayCore.reconfigure`): the bus client is rebuilt
   * with it once the request on the line now has its answer.
   */
  recalibrate(): void {
    this.stale = true;
    this.pump();
  }

  private newClient(): void {
    this.stale = false;
    this.client = createBusClient({
      protocol: this.protocol,
      servos: busCalibrations(this.joints),
    });
  }

  markReady(): void {
    this.ready = true;
  }

  /** A request with this tag is queued or on the line. */
  has(tag: BusJobTag): boolean {
    return this.current?.tag === tag || this.queue.some((j) => j.tag === tag);
  }

  /** Bytes that get no answer (a sync write). */
  send(bytes: Uint8Array, tag: BusJobTag, first = false): void {
    this.enqueue({ tag, make: () => bytes }, first);
  }

  dropGoals(): void {
    const before = this.queue.length;
    this.queue = this.queue.filter((j) => j.tag !== 'goal');
    this.counters.droppedGoals += before - this.queue.length;
  }

  /** Pings `ids` one by one; `done(found, missing)` after the last. */
  ping(ids: number[], done: (found: number[], missing: number[]) => void): void {
    const found: number[] = [];
    const missing: number[] = [];
    if (ids.length === 0) return done(found, missing);
    ids.forEach((id, k) =>
      this.enqueue(
        {
          tag: 'ping',
          make: (c) => c.ping(id),
          then: (r) => {
            (r?.kind === 'ping' && r.found ? found : missing).push(id);
            if (k === ids.length - 1) done(found, missing);
          },
        },
        false,
      ),
    );
  }

  readPositions(ids: number[], then: (r: Positions) => void, first = false): void {
    this.enqueue(
      {
        tag: 'positions',
        make: (c) => c.readPositions(ids),
        then: (r) =>
          then(r?.kind === 'positions' ? r : { kind: 'positions', servos: [], missing: ids }),
      },
      first,
    );
  }

  readHealth(ids: number[], then: (r: Health) => void): void {
    this.enqueue(
      {
        tag: 'health',
        make: (c) => c.readHealth(ids),
        then: (r) => then(r?.kind === 'health' ? r : { kind: 'health', servos: [], missing: ids }),
      },
      false,
    );
  }

  torque(on: boolean, ids: number[], first = false): void {
    if (ids.length) this.enqueue({ tag: 'torque', make: (c) => c.setTorque(on, ids) }, first);
  }

  /** A WRITE the servo acknowledges (or not: a missing answer is only counted). */
  config(id: number, w: ConfigWrite): void {
    this.enqueue(
      { tag: 'config', make: (c) => c.write(id, w.address, w.data), then: () => {} },
      false,
    );
  }

  fromSerial(chunk: Uint8Array): void {
    if (this.draining !== undefined) {
      this.counters.drainedBytes += chunk.length;
      return;
    }
    for (const r of this.client.feed(chunk)) this.finish(r);
  }

  private enqueue(job: Job, first: boolean): void {
    if (first) this.queue.unshift(job);
    else this.queue.push(job);
    this.pump();
  }

  private finish(result: BusResult | undefined): void {
    const job = this.current;
    if (!job) return;
    this.io.clearTimeout(this.timer);
    this.timer = undefined;
    this.current = undefined;
    job.then?.(result);
    this.pump();
  }

  private pump(): void {
    if (this.pumping || this.draining !== undefined) return;
    this.pumping = true;
    try {
      if (this.stale && !this.current) this.newClient();
      while (!this.current && this.queue.length) {
        const job = this.queue.shift()!;
        let bytes: Uint8Array;
        try {
          bytes = job.make(this.client);
        } catch (err) {
          this.counters.failed++;
          this.io.onFirst('bus:encode', `bus request not sent: ${(err as Error).message}`);
          job.then?.(undefined);
          continue;
        }
        this.counters.requests++;
        const pending = this.client.pending;
        if (job.then && pending) {
          this.current = job;
          this.timer = this.io.setTimeout(
            () => {
              this.timer = undefined;
              const r = this.client.expire();
              this.counters.timeouts++;
              this.newClient();
              this.draining = this.io.setTimeout(() => {
                this.draining = undefined;
                this.pump();
              }, BUS_DRAIN_MS);
              this.finish(r);
            },
            replyTimeoutMs(pending.expectedReplyBytes, this.baudRate),
          );
        }
        if (this.io.write(bytes)) this.counters.writes++;
        else this.counters.failed++;
      }
    } finally {
      this.pumping = false;
    }
  }
}
