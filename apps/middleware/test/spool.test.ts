import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterEach, describe, expect, test } from 'vitest';
import { Spool } from '../src/spool.ts';

const dirs: string[] = [];
const tmp = () => {
  const d = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-spool-test-'));
  dirs.push(d);
  return d;
};
afterEach(() => {
  for (const d of dirs.splice(0)) fs.rmSync(d, { recursive: true, force: true });
});

const lines = (from: number, n: number) =>
  Array.from(
    { length: n },
    (_, i) => `servo,arm=a,id=000 pwm=${1500 + ((from + i) % 100)}i ${from + i}`,
  );

/** One batch per file: how the spool kept batches before segments (and still can). */
const ONE = { segmentBatches: 1 };

describe('Spool, one batch per file', () => {
  test('appended points are on disk before seal; sealed batches come back oldest first', async () => {
    const dir = tmp();
    const s = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    s.init();
    s.append(lines(0, 3));
    expect(fs.readFileSync(path.join(dir, 'journal.lp'), 'utf8').split('\n')).toHaveLength(4);
    const a = s.seal()!;
    s.append(lines(3, 2));
    const b = s.seal()!;
    expect(s.seal()).toBeNull();
    expect(s.queue.map((e) => [e.seq, e.points])).toEqual([
      [a.seq, 3],
      [b.seq, 2],
    ]);
    expect(s.read(s.peek()!)).toBe(lines(0, 3).join('\n') + '\n');
    s.remove(a);
    expect(s.peek()).toBe(b);
    await s.settled(); // the file goes off the main thread
    expect(fs.readdirSync(path.join(dir, 'batches'))).toEqual([path.basename(b.segment!.file)]);
    expect(s.sealedPoints).toBe(2);
  });

  test('after a seal the journal goes on in a spare made ahead; spares stay empty and go at restart', async () => {
    const dir = tmp();
    const spares = () => fs.readdirSync(dir).filter((f) => f.startsWith('journal.next.'));
    const s1 = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    s1.init();
    expect(spares()).toHaveLength(3); // made at start, before the first seal needs one
    for (let k = 0; k < 5; k++) {
      s1.append(lines(k * 10, 10));
      s1.seal();
      s1.append(lines(k * 10 + 10, 1)); // the next journal takes appends at once
      expect(fs.readFileSync(path.join(dir, 'journal.lp'), 'utf8')).toBe(
        lines(k * 10 + 10, 1)[0] + '\n',
      );
      s1.seal();
    }
    await s1.settled();
    expect(spares().map((f) => fs.statSync(path.join(dir, f)).size)).toEqual([0, 0, 0]);
    s1.append(lines(900, 2)); // SIGKILL: no close
    const s2 = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0, ...ONE });
    expect(s2.init()).toEqual({ files: 11, points: 57 });
    expect(spares()).toHaveLength(3);
    const stored: string[] = [];
    for (let e = s2.peek(); e; e = s2.peek()) {
      stored.push(s2.read(e));
      s2.remove(e);
    }
    expect(stored.join('').trimEnd().split('\n').slice(-2)).toEqual(lines(900, 2));
    await s2.settled();
  });

  test('a restarted spool replays its batches in order, then the crashed journal (torn line cut)', async () => {
    const dir = tmp();
    const s1 = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    s1.init();
    for (let k = 0; k < 12; k++) {
      s1.append(lines(k * 10, 10));
      s1.seal();
    }
    s1.append(lines(500, 4));
    fs.appendFileSync(path.join(dir, 'journal.lp'), 'servo,arm=a,id=000 pwm=15'); // killed mid-write
    await s1.settled(); // its fsyncs and spare journals done (a killed process leaves none running)
    // SIGKILL: no close
    const s2 = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0, ...ONE });
    expect(s2.init()).toEqual({ files: 13, points: 124 });
    const bodies: string[] = [];
    while (s2.peek()) {
      const e = s2.peek()!;
      bodies.push(s2.read(e));
      s2.remove(e);
    }
    const all = bodies.join('').trimEnd().split('\n');
    expect(all).toEqual([...lines(0, 120), ...lines(500, 4)]);
    expect(fs.existsSync(path.join(dir, 'journal.lp'))).toBe(false);
    // sequence numbers go on after a restart, after any file still there
    s2.append(lines(0, 1));
    const kept = s2.seal()!;
    await s2.settled();
    const s3 = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    s3.init();
    s3.append(lines(0, 1));
    expect(s3.seal()!.seq).toBeGreaterThan(kept.seq);
    expect(s3.queue.map((e) => e.seq)).toEqual([kept.seq, kept.seq + 1]);
  });

  test('it is bounded: full at maxBytes, free again once batches leave', () => {
    const s = new Spool({ dir: tmp(), maxBytes: 2000, ...ONE });
    s.init();
    while (!s.full) {
      s.append(lines(0, 5));
      s.seal();
    }
    expect(s.bytes).toBeGreaterThanOrEqual(2000);
    s.remove(s.peek()!);
    expect(s.full).toBe(false);
  });

  test('a rejected batch moves to rejected/ with its reason and is not replayed', async () => {
    const dir = tmp();
    const s = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    s.init();
    s.append(lines(0, 2));
    const e = s.seal()!;
    const where = s.reject(e, '400 partial write: field type conflict');
    expect(fs.readFileSync(where, 'utf8')).toBe(lines(0, 2).join('\n') + '\n');
    expect(fs.readFileSync(`${where}.err`, 'utf8')).toMatch(/field type conflict/);
    await s.settled(); // the seal's fsync and the next spare journal, off the main thread
    const again = new Spool({ dir, maxBytes: 1 << 20, ...ONE });
    expect(again.init().files).toBe(0);
  });

  test('a disk failure keeps the batch in memory and reports it', () => {
    const dir = tmp();
    const errors: string[] = [];
    const s = new Spool({
      dir,
      maxBytes: 1 << 20,
      onDiskError: (op) => errors.push(op),
      ...ONE,
    });
    s.init();
    fs.rmSync(dir, { recursive: true });
    fs.writeFileSync(dir, 'not a dir');
    s.append(lines(0, 2));
    const e = s.seal()!;
    expect(errors).toContain('append');
    expect(e.segment).toBeNull();
    expect(s.read(e)).toBe(lines(0, 2).join('\n') + '\n');
    fs.rmSync(dir);
  });
});

describe('Spool, several batches per file (segments)', () => {
  const files = (dir: string) => fs.readdirSync(path.join(dir, 'batches')).sort();

  test('batches share a file, each read back from its range; a full file goes with its last batch', async () => {
    const dir = tmp();
    const s = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0, segmentBatches: 3 });
    s.init();
    const batches = [3, 1, 4, 1, 5, 9, 2].map((n, k) => {
      s.append(lines(k * 100, n));
      return s.seal()!;
    });
    // 7 batches: two full files of 3 in batches/ (named for their last batch), the 7th in the journal
    expect(files(dir)).toEqual([
      `${String(batches[2]!.seq).padStart(12, '0')}-8.lp`,
      `${String(batches[5]!.seq).padStart(12, '0')}-15.lp`,
    ]);
    expect(fs.readFileSync(path.join(dir, 'journal.lp'), 'utf8')).toBe(
      lines(600, 2).join('\n') + '\n',
    );
    // nothing cached: each batch is read from its range of the file
    expect(batches.map((b) => s.read(b))).toEqual(
      [3, 1, 4, 1, 5, 9, 2].map((n, k) => lines(k * 100, n).join('\n') + '\n'),
    );
    s.remove(batches[0]!);
    s.remove(batches[1]!);
    await s.settled();
    expect(files(dir)).toHaveLength(2); // its third batch is not written yet
    s.remove(batches[2]!);
    await s.settled();
    expect(files(dir)).toEqual([`${String(batches[5]!.seq).padStart(12, '0')}-15.lp`]);
    for (const b of batches.slice(3)) s.remove(b);
    await s.settled();
    // every batch written and no point open: no spool file is left
    expect(files(dir)).toEqual([]);
    expect(fs.existsSync(path.join(dir, 'journal.lp'))).toBe(false);
    s.append(lines(900, 1)); // and the next point starts a new journal
    expect(fs.readFileSync(path.join(dir, 'journal.lp'), 'utf8')).toBe(lines(900, 1)[0] + '\n');
    s.close();
    await s.settled();
  });

  test('killed mid-segment, a restart replays every file whole in order (written batches too), the torn line cut', async () => {
    const dir = tmp();
    const s1 = new Spool({ dir, maxBytes: 1 << 20, segmentBatches: 4 });
    s1.init();
    const sealed = Array.from({ length: 10 }, (_, k) => {
      s1.append(lines(k * 10, 10));
      return s1.seal()!;
    });
    s1.remove(sealed[0]!); // InfluxDB has these two: their file stays for the other two
    s1.remove(sealed[1]!);
    s1.append(lines(500, 3));
    fs.appendFileSync(path.join(dir, 'journal.lp'), 'servo,arm=a,id=000 pwm=15'); // killed mid-write
    await s1.settled();
    // SIGKILL: no close
    const s2 = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0, segmentBatches: 4 });
    expect(s2.init()).toEqual({ files: 3, points: 103 });
    const bodies: string[] = [];
    const seqs: number[] = [];
    for (let e = s2.peek(); e; e = s2.peek()) {
      bodies.push(s2.read(e));
      seqs.push(e.seq);
      s2.remove(e);
    }
    expect(bodies.join('').trimEnd().split('\n')).toEqual([...lines(0, 100), ...lines(500, 3)]);
    expect(seqs).toEqual([...seqs].sort((a, b) => a - b));
    await s2.settled();
    expect(files(dir)).toEqual([]);
    s2.append(lines(0, 1)); // numbering goes on after every file
    expect(s2.seal()!.seq).toBeGreaterThan(Math.max(...seqs));
    s2.close();
  });

  test('a stop keeps the journal only while it holds a batch InfluxDB does not have', async () => {
    const dir = tmp();
    const journal = path.join(dir, 'journal.lp');
    const s1 = new Spool({ dir, maxBytes: 1 << 20 });
    s1.init();
    s1.append(lines(0, 2));
    const written = s1.seal()!;
    s1.append(lines(2, 2));
    const waiting = s1.seal()!;
    s1.remove(written);
    s1.close();
    await s1.settled();
    expect(fs.existsSync(journal)).toBe(true);
    const s2 = new Spool({ dir, maxBytes: 1 << 20 });
    expect(s2.init()).toEqual({ files: 1, points: 4 }); // the written batch comes again with it
    expect(s2.read(s2.peek()!)).toBe(lines(0, 4).join('\n') + '\n');
    s2.remove(s2.peek()!);
    s2.append(lines(9, 1));
    s2.remove(s2.seal()!);
    s2.close();
    await s2.settled();
    expect(fs.existsSync(journal)).toBe(false);
    expect(new Spool({ dir, maxBytes: 1 << 20 }).init()).toEqual({ files: 0, points: 0 });
    void waiting;
  });

  test('a failed append leaves its batch in memory, and the next batch overwrites its range', () => {
    const dir = tmp();
    const errors: string[] = [];
    const s = new Spool({ dir, maxBytes: 1 << 20, onDiskError: (op) => errors.push(op) });
    s.init();
    s.append(lines(0, 2));
    const first = s.seal()!;
    const write = fs.writeSync;
    let fail = true;
    const spy = ((...a: Parameters<typeof fs.writeSync>) => {
      if (fail) {
        fail = false;
        write(a[0], 'servo,arm=a,id=000 pw', a[2] as number, 'latin1'); // a short write
        throw Object.assign(new Error('ENOSPC: no space left on device'), { code: 'ENOSPC' });
      }
      return (write as (...x: unknown[]) => number)(...a);
    }) as typeof fs.writeSync;
    fs.writeSync = spy;
    try {
      s.append(lines(2, 2));
    } finally {
      fs.writeSync = write;
    }
    const lost = s.seal()!;
    s.append(lines(4, 2));
    const next = s.seal()!;
    expect(errors).toEqual(['append']);
    expect(lost.segment).toBeNull();
    expect(s.read(lost)).toBe(lines(2, 2).join('\n') + '\n');
    expect(next.offset).toBe(first.bytes);
    expect(fs.readFileSync(path.join(dir, 'journal.lp'), 'latin1')).toBe(
      [...lines(0, 2), ...lines(4, 2)].join('\n') + '\n',
    );
    s.close();
  });
});
