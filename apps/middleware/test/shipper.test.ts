import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { pino } from 'pino';
import { afterEach, describe, expect, test, vi } from 'vitest';
import { Batcher } from '../src/batcher.ts';
import { WriteError, type InfluxWriter } from '../src/influx.ts';
import { LogOnce } from '../src/log.ts';
import { Metrics } from '../src/metrics.ts';
import { retryDelay, Shipper, type Clock } from '../src/shipper.ts';
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

function setup(opts = { minRetryDelayMs: 100, maxRetryDelayMs: 1000 }) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-shipper-test-'));
  const spool = new Spool({ dir, maxBytes: 1 << 20 });
  spool.init();
  const writer = new FakeWriter();
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
