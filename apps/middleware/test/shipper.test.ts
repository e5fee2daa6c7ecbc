import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pino } from 'pino';
import { afterEach, describe, expect, test, vi } from 'vitest';
import { Batcher } from '../src/batcher.ts';
import { WriteError, type InfluxWriter } from '../src/influx.ts';
import { LogOnce } from '../src/log.ts';
import { Metrics } from '../src/metrics.ts';
import type { Clock } from '@armtwin/protocol';
import { retryDelay, Shipper, type ShipperOptions } from '../src/shipper.ts';
import { Spool } from '../src/spool.ts';

afterEach(() => vi.useRealTimers());

/** A Clock on vitest's fake timers. */
const fakeClock = (): Clock => ({
  now: () => Date.now(),
  setTimeout: (f, ms) => setTimeout(f, ms),
  clearTimeout: (h) => clearTimeout(h as number),
});

class FakeWriter implements InfluxWriter {
  bodies: string[] = [];
  failures: (WriteError | null)[] = [];
  async write(body: string) {
    const f = this.failures.shift();
    if (f) throw f;
    this.bodies.push(body);
  }
  async ping() {
    return true;
  }
  async ensureBucket() {
    return 'ok';
  }
}

function setup(
  opts: ShipperOptions = { minRetryDelayMs: 100, maxRetryDelayMs: 1000 },
  writer = new FakeWriter(),
) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-shipper-test-'));
  const spool = new Spool({ dir, maxBytes: 1 << 20 });
  spool.init();
  const metrics = new Metrics();
  const log = pino({ level: 'silent' });
  const shipper = new Shipper(spool, writer, metrics, log, new LogOnce(log), opts, fakeClock());
  const add = (n: string) => {
    spool.append([n]);
    spool.seal();
  };
  return { dir, spool, writer, metrics, shipper, add };
}

describe('retryDelay', () => {
  test('doubles from the minimum and is capped at MAX_RETRY_DELAY_MS', () => {
    const o = { minRetryDelayMs: 500, maxRetryDelayMs: 15000 };
    expect([1, 2, 3, 4, 5, 6, 7, 50].map((n) => retryDelay(n, o))).toEqual([
      500, 1000, 2000, 4000, 8000, 15000, 15000, 15000,
    ]);
  });
});

describe('Shipper', () => {
  test('ships oldest first; while InfluxDB is down it keeps every batch and backs off', async () => {
    vi.useFakeTimers();
    const { spool, writer, metrics, shipper, add, dir } = setup();
    writer.failures = [
      new WriteError('network', 'ECONNREFUSED'),
      new WriteError('http', '503'),
      new WriteError('network', 'x'),
    ];
    add('a 1');
    add('b 2');
    shipper.kick();
    add('c 3');
    shipper.kick();
    await vi.advanceTimersByTimeAsync(99);
    expect(writer.bodies).toEqual([]);
    expect(spool.queue).toHaveLength(3);
    await vi.advanceTimersByTimeAsync(100 + 200 + 400);
    expect(writer.bodies).toEqual(['a 1\n', 'b 2\n', 'c 3\n']);
    expect(metrics).toMatchObject({ retries: 3, pointsWritten: 3, pointsDropped: 0 });
    expect(metrics.batches).toMatchObject({ ok: 3, failed: 3 });
    expect(spool.queue).toHaveLength(0);
    await spool.settled(); // its disk work off the main thread (fsyncs, the next journals)
    fs.rmSync(dir, { recursive: true });
  });

  test('bad data (400) goes to rejected/ once and does not block later batches', async () => {
    const { spool, writer, metrics, shipper, add, dir } = setup();
    writer.failures = [new WriteError('data', '400 partial write: field type conflict', 400)];
    add('bad 1');
    add('good 2');
    shipper.kick();
    await vi.waitFor(() => expect(spool.queue).toHaveLength(0));
    expect(writer.bodies).toEqual(['good 2\n']);
    expect(metrics.pointsRejected).toBe(1);
    expect(fs.readdirSync(path.join(dir, 'rejected'))).toHaveLength(2);
    await spool.settled(); // its disk work off the main thread (fsyncs, the next journals)
    fs.rmSync(dir, { recursive: true });
  });
});

/** A writer whose requests wait until the test answers them: shows what is in flight at once. */
class HeldWriter extends FakeWriter {
  held: { body: string; ok: () => void; fail: (e: Error) => void }[] = [];
  override write(body: string) {
    return new Promise<void>((ok, fail) => this.held.push({ body, ok, fail }));
  }
  /** Answers every held request (ok or failed), oldest first. */
  answer(result: 'ok' | WriteError) {
    for (const h of this.held.splice(0)) {
      if (result === 'ok') {
        this.bodies.push(h.body);
        h.ok();
      } else h.fail(result);
    }
  }
}

describe('Shipper, concurrent writes', () => {
  test('keeps WRITE_CONCURRENCY batches in flight, oldest first; a failure drops to one prober, and its success brings the rest back', async () => {
    vi.useFakeTimers();
    const writer = new HeldWriter();
    const { spool, metrics, shipper, add, dir } = setup(
      { minRetryDelayMs: 100, maxRetryDelayMs: 1000, writeConcurrency: 3 },
      writer,
    );
    for (const n of ['a', 'b', 'c', 'd', 'e', 'f', 'g']) add(`${n} 1`);
    shipper.kick();
    await vi.advanceTimersByTimeAsync(0);
    expect(writer.held.map((h) => h.body)).toEqual(['a 1\n', 'b 1\n', 'c 1\n']);
    writer.answer(new WriteError('network', 'ECONNREFUSED'));
    await vi.advanceTimersByTimeAsync(0);
    expect(writer.held).toHaveLength(0); // backing off: nothing in flight
    expect(spool.queue).toHaveLength(7); // and nothing lost
    await vi.advanceTimersByTimeAsync(400);
    expect(writer.held.map((h) => h.body)).toEqual(['a 1\n']); // one probe, the oldest
    writer.answer('ok');
    await vi.advanceTimersByTimeAsync(0);
    expect(writer.held.map((h) => h.body)).toEqual(['b 1\n', 'c 1\n', 'd 1\n']);
    writer.answer('ok');
    await vi.advanceTimersByTimeAsync(0);
    writer.answer('ok');
    await vi.advanceTimersByTimeAsync(0);
    expect(writer.bodies).toEqual(['a 1\n', 'b 1\n', 'c 1\n', 'd 1\n', 'e 1\n', 'f 1\n', 'g 1\n']);
    expect(spool.queue).toHaveLength(0);
    expect(metrics).toMatchObject({ pointsWritten: 7, pointsDropped: 0 });
    await shipper.stop();
    await spool.settled(); // its disk work off the main thread (fsyncs, the next journals)
    fs.rmSync(dir, { recursive: true });
  });
});

describe('Batcher', () => {
  test('flushes at BATCH_SIZE points or FLUSH_INTERVAL_MS after the first point', () => {
    vi.useFakeTimers();
    const flush = vi.fn();
    const b = new Batcher({ batchSize: 10, flushIntervalMs: 5000 }, flush, fakeClock());
    b.added(4);
    b.added(6);
    expect(flush).toHaveBeenCalledTimes(1);
    b.added(3);
    vi.advanceTimersByTime(4999);
    expect(flush).toHaveBeenCalledTimes(1);
    vi.advanceTimersByTime(1);
    expect(flush).toHaveBeenCalledTimes(2);
    vi.advanceTimersByTime(60_000);
    expect(flush).toHaveBeenCalledTimes(2); // nothing pending, no empty flushes
  });
});
