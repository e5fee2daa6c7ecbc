/** One pino logger per command, to stderr (stdout stays free for data, e.g. `up`'s URL). */
import { pino, type Logger } from 'pino';

export function createLogger(name: string, level = 'info'): Logger {
  return pino({ name, level, base: undefined }, pino.destination({ fd: 2, sync: false }));
}

/** Logs each kind once, at warn; later ones of the same kind are only counted by the caller. */
export function firstOnly(log: Logger): (kind: string, message: string) => void {
  const seen = new Set<string>();
  return (kind, message) => {
    if (seen.has(kind)) return;
    seen.add(kind);
    log.warn({ kind }, `${message} (further ${kind} problems are counted, not logged)`);
  };
}
