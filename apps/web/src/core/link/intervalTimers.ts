/**
 * Interval timers for the deadman's beat. The page passes worker-timers (as mqtt.js does for
 * its keep-alive), so a hidden tab keeps beating while a frozen one does not.
 */
export interface IntervalTimers {
  setInterval(fn: () => void, ms: number): number;
  clearInterval(id: number): void;
}

/** The window's own timers (unit tests, and a page without worker-timers). */
export const NATIVE_INTERVALS: IntervalTimers = {
  setInterval: (fn, ms) => setInterval(fn, ms) as unknown as number,
  clearInterval: (id) => clearInterval(id),
};
