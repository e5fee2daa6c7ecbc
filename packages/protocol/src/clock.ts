/**
 * Time and timers, injected so that the parts that keep time (the simulator's loops, the
 * gateway's deadman, `OperatorWatch`) can be tested with a manual clock (`./fake-clock.ts`).
 */
import type { OperatorTimers } from './operator.ts';

export interface Clock extends OperatorTimers {
  /** Unix epoch ms (fractional allowed), non-decreasing. */
  now(): number;
}

const origin = performance.timeOrigin;

/** Epoch time from the monotonic clock: never steps backwards while the process runs. */
export const SYSTEM_CLOCK: Clock = {
  now: () => origin + performance.now(),
  setTimeout: (fn, ms) => setTimeout(fn, ms),
  clearTimeout: (h) => clearTimeout(h as ReturnType<typeof setTimeout>),
};
