/**
 * A fixed-rate loop that does not drift: tick k is due at `start + k · period` (computed, not
 * accumulated), and the timer is always set for the next due tick against absolute time. When
 * a wake-up comes late, every tick that fell due is handed over in one batch (the state stream
 * then sends them in one payload, each with its own `$TIM`); a batch is capped, and a loop more
 * than `maxBatch` ticks behind (a suspended process) skips ahead and counts what it skipped.
 */
import type { Clock } from '@armtwin/protocol';

export interface TickLoopOptions {
  /** Ticks per second. */
  hz: number;
  /** Most ticks handed over in one wake-up. */
  maxBatch: number;
}

export const DEFAULT_TICK_LOOP_OPTIONS: TickLoopOptions = { hz: 50, maxBatch: 32 };

/** Called with the due times (epoch ms) in `times[0 … count-1]`; the array is reused. */
export type TickHandler = (times: Float64Array, count: number) => void;

export class TickLoop {
  readonly period: number;
  private readonly maxBatch: number;
  private readonly times: Float64Array;
  private start = 0;
  private k = 0;
  private timer: unknown = undefined;
  private running = false;
  /** Ticks skipped because the loop fell more than maxBatch behind. */
  skipped = 0;
  /** Wake-ups that handed over more than one tick. */
  batches = 0;

  constructor(
    private readonly clock: Clock,
    private readonly onTicks: TickHandler,
    options: Partial<TickLoopOptions> = {},
  ) {
    const o = { ...DEFAULT_TICK_LOOP_OPTIONS, ...options };
    if (!(o.hz > 0)) throw new RangeError(`tick rate must be > 0, got ${o.hz}`);
    this.period = 1000 / o.hz;
    this.maxBatch = Math.max(1, o.maxBatch);
    this.times = new Float64Array(this.maxBatch);
  }

  /** First tick one period from now. */
  startLoop(): void {
    if (this.running) return;
    this.running = true;
    this.start = this.clock.now();
    this.k = 1;
    this.schedule();
  }

  stopLoop(): void {
    this.running = false;
    if (this.timer !== undefined) this.clock.clearTimeout(this.timer);
    this.timer = undefined;
  }

  /** Hands over every tick already due (e.g. before a command changes the model). */
  catchUp(): void {
    if (!this.running) return;
    const now = this.clock.now();
    let due = Math.floor((now - this.start) / this.period) - this.k + 1;
    if (due <= 0) return;
    if (due > this.maxBatch) {
      this.skipped += due - this.maxBatch;
      this.k += due - this.maxBatch;
      due = this.maxBatch;
    }
    for (let j = 0; j < due; j++) this.times[j] = this.start + (this.k + j) * this.period;
    this.k += due;
    if (due > 1) this.batches++;
    this.onTicks(this.times, due);
  }

  private readonly wake = () => {
    this.timer = undefined;
    if (!this.running) return;
    this.catchUp();
    if (this.running) this.schedule();
  };

  private schedule(): void {
    const next = this.start + this.k * this.period;
    const delay = Math.max(1, Math.ceil(next - this.clock.now()));
    this.timer = this.clock.setTimeout(this.wake, delay);
  }
}
