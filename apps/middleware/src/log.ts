/**
 * pino, plus "log the first occurrence of each error kind, then only count it": a stream of
 * bad frames or a long outage must not flood the log.
 */
import { pino, type Logger } from 'pino';

export type { Logger };

export function createLogger(level: string, name = 'middleware'): Logger {
  return pino({ name, level });
}

export class LogOnce {
  private readonly seen = new Map<string, number>();
  constructor(private readonly log: Logger) {}

  /** Logs at `level` the first time `kind` happens (and every `every`-th time after). */
  warn(kind: string, obj: object, msg: string, every = 0): void {
    const n = (this.seen.get(kind) ?? 0) + 1;
    this.seen.set(kind, n);
    if (n === 1) this.log.warn({ ...obj, kind }, `${msg} (logged once; counted in /metrics)`);
    else if (every > 0 && n % every === 0) this.log.warn({ ...obj, kind, occurrences: n }, msg);
  }

  /** Forgets `kind`, so its next occurrence is logged again (e.g. after a recovery). */
  reset(kind: string): void {
    this.seen.delete(kind);
  }

  count(kind: string): number {
    return this.seen.get(kind) ?? 0;
  }
}
