/**
 * One `fs.watchFile` per file for everyone in the process who follows it. Node keeps one stat
 * watcher per file and adds one `change` listener to it per `fs.watchFile` call, so more than
 * ten followers of one file (many simulated arms of one profile in one process: the fleet
 * bench, the cluster bench, `armtwin up` with many arms) print Node's
 * MaxListenersExceededWarning. Here each file has one listener that tells every follower.
 * The file is polled at the first follower's interval, as Node does for a second `watchFile`.
 */
import fs from 'node:fs';
import path from 'node:path';

export type FileChange = (now: fs.Stats, before: fs.Stats) => void;

const followers = new Map<string, Set<FileChange>>();

/** Follows `file`'s changes (stat polled every `intervalMs`); returns the way to stop. */
export function followFile(file: string, intervalMs: number, onChange: FileChange): () => void {
  const key = path.resolve(file);
  let set = followers.get(key);
  if (!set) {
    const all = (set = new Set());
    followers.set(key, all);
    fs.watchFile(key, { interval: intervalMs, persistent: false }, (now, before) => {
      for (const f of [...all]) f(now, before);
    });
  }
  const mine = (now: fs.Stats, before: fs.Stats) => onChange(now, before);
  set.add(mine);
  return () => {
    if (!set.delete(mine) || set.size > 0) return;
    followers.delete(key);
    fs.unwatchFile(key);
  };
}

/** The files followed now (tests). */
export const followedFiles = (): number => followers.size;
