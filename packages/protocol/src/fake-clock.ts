/**
 * A manual clock for unit tests (`@armtwin/protocol/fake-clock`, kept out of the main entry):
 * `advance(ms)` fires due timers in time order.
 */
import type { Clock } from './clock.ts';

export class FakeClock implements Clock {
  private t: number;
  private seq = 0;
  private timers = new Map<number, { at: number; fn: () => void }>();

  constructor(start = 1_700_000_000_000) {
    this.t = start;
  }

  now(): number {
    return this.t;
  }

  setTimeout(fn: () => void, ms: number): unknown {
    const id = ++this.seq;
    this.timers.set(id, { at: this.t + ms, fn });
    return id;
  }

  clearTimeout(handle: unknown): void {
    this.timers.delete(handle as number);
  }

  /** Moves time forward by ms, running timers as they fall due (optionally each `late` ms late). */
  advance(ms: number, late = 0): void {
    const end = this.t + ms;
    for (;;) {
      let next: [number, { at: number; fn: () => void }] | undefined;
      for (const entry of this.timers) if (!next || entry[1].at < next[1].at) next = entry;
      if (!next || next[1].at + late > end) break;
      this.timers.delete(next[0]);
      this.t = Math.max(this.t, next[1].at + late);
      next[1].fn();
    }
    this.t = end;
  }
}
