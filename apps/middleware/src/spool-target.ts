/**
 * One spool folder per destination. A batch is durable before InfluxDB has it, so it must
 * remember where it was going: a middleware restarted with another INFLUX_URL, org or bucket
 * must not write the old run's batches there. Each destination gets its own folder under
 * SPOOL_DIR, named for it and holding `target.json`; a run ships only its own folder and says
 * (log, /metrics) what waits in the others, to be written when a run is configured for them.
 *
 *   <SPOOL_DIR>/<host_port>.<org>.<bucket>.<hash>/{target.json, journal.lp, batches/, rejected/}
 *
 * A spool written before this layout (batches/ and journal.lp straight in SPOOL_DIR) recorded no
 * destination; it is adopted by the first run, and the log says so.
 */
import { createHash } from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';

/** Where a batch is meant to go. */
export interface SpoolTarget {
  url: string;
  org: string;
  bucket: string;
}

export interface OtherTarget {
  target: SpoolTarget;
  dir: string;
  files: number;
  points: number;
}

const TARGET_FILE = 'target.json';
const BATCH = /^\d{12}-(\d+)\.lp$/;
const LEGACY = ['batches', 'rejected', 'journal.lp'];

const slug = (s: string) => s.replace(/[^A-Za-z0-9_-]+/g, '_').slice(0, 40) || '_';

/** The folder name of a destination: readable, and unique by a hash of the exact settings. */
export function targetKey(t: SpoolTarget): string {
  let host = t.url;
  try {
    host = new URL(t.url).host;
  } catch {
    // not a URL: the slug of the text will do
  }
  const hash = createHash('sha256')
    .update(JSON.stringify([t.url.replace(/\/+$/, ''), t.org, t.bucket]))
    .digest('hex')
    .slice(0, 10);
  return `${slug(host)}.${slug(t.org)}.${slug(t.bucket)}.${hash}`;
}

/** What waits in a spool folder: files, and points (from the names, and the journal's lines). */
function waiting(dir: string): { files: number; points: number } {
  let files = 0;
  let points = 0;
  let names: string[] = [];
  try {
    names = fs.readdirSync(path.join(dir, 'batches'));
  } catch {
    // no batches folder: nothing waits
  }
  for (const name of names) {
    const m = BATCH.exec(name);
    if (!m) continue;
    files++;
    points += Number(m[1]);
  }
  try {
    const journal = fs.readFileSync(path.join(dir, 'journal.lp'), 'latin1');
    files++;
    for (let i = journal.indexOf('\n'); i >= 0; i = journal.indexOf('\n', i + 1)) points++;
  } catch {
    // no journal
  }
  return { files, points };
}

/**
 * Makes (or finds) the folder of `target` under `root`: moves a spool of the old layout into it,
 * writes target.json, and lists the other destinations with batches waiting.
 */
export function prepareSpoolTarget(
  root: string,
  target: SpoolTarget,
): { dir: string; adoptedLegacy: boolean; others: OtherTarget[] } {
  fs.mkdirSync(root, { recursive: true });
  const key = targetKey(target);
  const dir = path.join(root, key);
  fs.mkdirSync(dir, { recursive: true });
  let adoptedLegacy = false;
  for (const name of LEGACY) {
    const from = path.join(root, name);
    if (!fs.existsSync(from)) continue;
    const to = path.join(dir, name);
    if (fs.existsSync(to) && fs.statSync(from).isDirectory()) {
      for (const f of fs.readdirSync(from)) fs.renameSync(path.join(from, f), path.join(to, f));
      fs.rmdirSync(from);
    } else fs.renameSync(from, to);
    adoptedLegacy = true;
  }
  fs.writeFileSync(path.join(dir, TARGET_FILE), JSON.stringify(target, null, 2) + '\n');
  const others: OtherTarget[] = [];
  for (const name of fs.readdirSync(root)) {
    if (name === key) continue;
    const other = path.join(root, name);
    let t: SpoolTarget;
    try {
      t = JSON.parse(fs.readFileSync(path.join(other, TARGET_FILE), 'utf8')) as SpoolTarget;
    } catch {
      continue; // not a destination folder
    }
    const w = waiting(other);
    if (w.files > 0) others.push({ target: t, dir: other, ...w });
  }
  return { dir, adoptedLegacy, others };
}
