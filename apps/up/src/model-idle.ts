/**
 * When a model copy stops by itself (docs/protocol.md § Modes): after `idleMs` with no activity
 * (nothing received on its topics, no `POST`). One timer per copy, not one per message: `touch`
 * only notes the time, and the timer, when it fires, sleeps again for what is left. The clock is
 * injected (a fake one in tests); no I/O.
 */
import type { Clock } from '@armtwin/protocol';

/** ms until a copy last active at `lastActivity` is idle (≤ 0: idle now). */
export function idleLeftMs(lastActivity: number, now: number, idleMs: number): number {
  return lastActivity + idleMs - now;
}

export class IdleWatch {
  private last: number;
  private timer: unknown;

  constructor(
    private readonly clock: Clock,
    private readonly idleMs: number,
    private readonly onIdle: () => void,
  ) {
    this.last = clock.now();
    this.arm(idleMs);
  }

  /** Something happened: the idle time starts again. */
  touch(): void {
    this.last = this.clock.now();
  }

  /** No more `onIdle`. */
  stop(): void {
    if (this.timer !== undefined) this.clock.clearTimeout(this.timer);
    this.timer = undefined;
  }

  private arm(ms: number): void {
    this.timer = this.clock.setTimeout(() => {
      const left = idleLeftMs(this.last, this.clock.now(), this.idleMs);
      if (left > 0) return this.arm(left);
      this.timer = undefined;
      this.onIdle();
    }, ms);
  }
}
