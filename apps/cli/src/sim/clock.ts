/** Time and timers, injected so that the runner and the loop can be tested with a fake clock. */
export interface Clock {
  /** Unix epoch ms (fractional allowed), non-decreasing. */
  now(): number;
  setTimeout(fn: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
}

const origin = performance.timeOrigin;

/** Epoch time from the monotonic clock: never steps backwards while the process runs. */
export const SYSTEM_CLOCK: Clock = {
  now: () => origin + performance.now(),
  setTimeout: (fn, ms) => setTimeout(fn, ms),
  clearTimeout: (h) => clearTimeout(h as NodeJS.Timeout),
};
