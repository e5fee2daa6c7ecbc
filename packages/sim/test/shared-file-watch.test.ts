/**
 * Many followers of one file in one process (fifty simulated arms of one profile): one watcher
 * for the file, each follower told of a change, no MaxListenersExceededWarning; a follower that
 * stops is told nothing more, and the file is let go with the last one.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, expect, test } from 'vitest';
import { followedFiles, followFile } from '../src/shared-file-watch.ts';

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-watch-'));
afterAll(() => fs.rmSync(dir, { recursive: true, force: true }));

const until = async (fn: () => boolean, what: string) => {
  for (const end = Date.now() + 10_000; !fn(); await new Promise((r) => setTimeout(r, 10)))
    if (Date.now() > end) throw new Error(`timed out waiting for ${what}`);
};

test('fifty followers of one file: one watcher, each told of a change, no listener warning', async () => {
  const file = path.join(dir, 'profile.json');
  fs.writeFileSync(file, '{}');
  const warnings: string[] = [];
  const onWarning = (w: Error) => warnings.push(w.name);
  process.on('warning', onWarning);
  try {
    const told = Array.from({ length: 50 }, () => 0);
    const stops = told.map((_, k) => followFile(file, 20, () => told[k]!++));
    expect(followedFiles()).toBe(1);

    fs.writeFileSync(file, '{"changed":1}');
    fs.utimesSync(file, new Date(), new Date(Date.now() + 5000));
    await until(() => told.every((n) => n > 0), 'every follower told');

    // Forty-nine stop: the last one is still told; the others are not.
    for (const stop of stops.slice(0, 49)) stop();
    const before = [...told];
    fs.utimesSync(file, new Date(), new Date(Date.now() + 10_000));
    await until(() => told[49]! > before[49]!, 'the last follower told');
    expect(told.slice(0, 49)).toEqual(before.slice(0, 49));

    stops[49]!();
    expect(followedFiles()).toBe(0);
    await new Promise((r) => setImmediate(r));
    expect(warnings).toEqual([]);
  } finally {
    process.off('warning', onWarning);
  }
});
