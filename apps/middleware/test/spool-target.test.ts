import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterEach, describe, expect, test } from 'vitest';
import { Spool } from '../src/spool.ts';
import { prepareSpoolTarget, targetKey } from '../src/spool-target.ts';

const dirs: string[] = [];
const tmp = () => {
  const d = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-spool-target-'));
  dirs.push(d);
  return d;
};
afterEach(() => {
  for (const d of dirs.splice(0)) fs.rmSync(d, { recursive: true, force: true });
});

const A = { url: 'http://influx:8086', org: 'lab', bucket: 'armtwin' };
const B = { ...A, bucket: 'other' };

/** Spools `n` points into the destination's folder and leaves them sealed (InfluxDB was down). */
function spoolFor(root: string, target: typeof A, n: number): void {
  const { dir } = prepareSpoolTarget(root, target);
  const s = new Spool({ dir, maxBytes: 1 << 20 });
  s.init();
  s.append(Array.from({ length: n }, (_, i) => `servo,arm=a,id=000 pwm=1500i ${i}`));
  s.seal();
  s.close();
}

describe('per-destination spool folders', () => {
  test('each URL, org and bucket has its own folder; a trailing slash is the same URL', () => {
    expect(targetKey(A)).not.toBe(targetKey(B));
    expect(targetKey(A)).not.toBe(targetKey({ ...A, org: 'other' }));
    expect(targetKey(A)).not.toBe(targetKey({ ...A, url: 'http://influx2:8086' }));
    expect(targetKey({ ...A, url: 'http://influx:8086/' })).toBe(targetKey(A));
    expect(targetKey(A)).toMatch(/^influx_8086\.lab\.armtwin\.[0-9a-f]{10}$/);
  });

  test("a run for B never sees A's batches, and says they wait; a run for A gets them back", () => {
    const root = tmp();
    spoolFor(root, A, 7);
    const forB = prepareSpoolTarget(root, B);
    const spoolB = new Spool({ dir: forB.dir, maxBytes: 1 << 20 });
    expect(spoolB.init()).toEqual({ files: 0, points: 0 });
    expect(forB.others).toEqual([
      { target: A, dir: path.join(root, targetKey(A)), files: 1, points: 7 },
    ]);
    const forA = prepareSpoolTarget(root, A);
    expect(new Spool({ dir: forA.dir, maxBytes: 1 << 20 }).init()).toEqual({ files: 1, points: 7 });
    expect(forA.others).toEqual([]);
    expect(JSON.parse(fs.readFileSync(path.join(forA.dir, 'target.json'), 'utf8'))).toEqual(A);
  });

  test('a spool of the old layout (no record of its bucket) is adopted by the first run', () => {
    const root = tmp();
    const old = new Spool({ dir: root, maxBytes: 1 << 20, segmentBatches: 1 }); // as it was: a file a batch
    old.init();
    old.append(['servo,arm=a,id=000 pwm=1500i 1', 'servo,arm=a,id=000 pwm=1500i 2']);
    old.seal();
    old.append(['servo,arm=a,id=000 pwm=1500i 3']); // left open in the journal
    old.close();
    const r = prepareSpoolTarget(root, A);
    expect(r.adoptedLegacy).toBe(true);
    expect(fs.existsSync(path.join(root, 'batches'))).toBe(false);
    expect(new Spool({ dir: r.dir, maxBytes: 1 << 20 }).init()).toEqual({ files: 2, points: 3 });
    expect(prepareSpoolTarget(root, A).adoptedLegacy).toBe(false);
  });
});
