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

describe('Spool', () => {
  test('appended points are on disk before seal; sealed batches come back oldest first', async () => {
    const dir = tmp();
    const s = new Spool({ dir, maxBytes: 1 << 20 });
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
    expect(fs.readdirSync(path.join(dir, 'batches'))).toEqual([path.basename(b.file!)]);
    expect(s.sealedPoints).toBe(2);
  });

  test('after a seal the journal goes on in a spare made ahead; spares stay empty and go at restart', async () => {
    const dir = tmp();
    const spares = () => fs.readdirSync(dir).filter((f) => f.startsWith('journal.next.'));
    const s1 = new Spool({ dir, maxBytes: 1 << 20 });
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
    const s2 = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0 });
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
    const s1 = new Spool({ dir, maxBytes: 1 << 20 });
    s1.init();
    for (let k = 0; k < 12; k++) {
      s1.append(lines(k * 10, 10));
      s1.seal();
    }
    s1.append(lines(500, 4));
    fs.appendFileSync(path.join(dir, 'journal.lp'), 'servo,arm=a,id=000 pwm=15'); // killed mid-write
    await s1.settled(); // its fsyncs and spare journals done (a killed process leaves none running)
    // SIGKILL: no close
    const s2 = new Spool({ dir, maxBytes: 1 << 20, cacheBytes: 0 });
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
    const s3 = new Spool({ dir, maxBytes: 1 << 20 });
    s3.init();
    s3.append(lines(0, 1));
    expect(s3.seal()!.seq).toBeGreaterThan(kept.seq);
    expect(s3.queue.map((e) => e.seq)).toEqual([kept.seq, kept.seq + 1]);
  });

  test('it is bounded: full at maxBytes, free again once batches leave', () => {
    const s = new Spool({ dir: tmp(), maxBytes: 2000 });
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
    const s = new Spool({ dir, maxBytes: 1 << 20 });
    s.init();
    s.append(lines(0, 2));
    const e = s.seal()!;
    const where = s.reject(e, '400 partial write: field type conflict');
    expect(fs.readFileSync(where, 'utf8')).toBe(lines(0, 2).join('\n') + '\n');
    expect(fs.readFileSync(`${where}.err`, 'utf8')).toMatch(/field type conflict/);
    await s.settled(); // the seal's fsync and the next spare journal, off the main thread
    const again = new Spool({ dir, maxBytes: 1 << 20 });
    expect(again.init().files).toBe(0);
  });

  test('a disk failure keeps the batch in memory and reports it', () => {
    const dir = tmp();
    const errors: string[] = [];
    const s = new Spool({ dir, maxBytes: 1 << 20, onDiskError: (op) => errors.push(op) });
    s.init();
    fs.rmSync(dir, { recursive: true });
    fs.writeFileSync(dir, 'not a dir');
    s.append(lines(0, 2));
    const e = s.seal()!;
    expect(errors).toContain('append');
    expect(e.file).toBeNull();
    expect(s.read(e)).toBe(lines(0, 2).join('\n') + '\n');
    fs.rmSync(dir);
  });
});
