/**
 * Retry back-off, the one rule for every reconnect and restart (the middleware's InfluxDB
 * writes, the gateway's serial port, the camera server's ffmpeg, the page's camera streams):
 * the first retry waits `minMs`, each further one `factor` (default 2) times longer, never more
 * than `maxMs`. A success starts again from `minMs`.
 */
export interface Backoff {
  /** The first retry's delay, ms. */
  minMs: number;
  /** The longest delay, ms. */
  maxMs: number;
  /** Growth per failure (default 2). */
  factor?: number;
}

/** The delay before the next retry after `failures` failures in a row (0: the first retry). */
export const backoffDelay = (failures: number, b: Backoff): number =>
  Math.min(b.maxMs, b.minMs * (b.factor ?? 2) ** Math.min(1000, Math.max(0, failures)));
