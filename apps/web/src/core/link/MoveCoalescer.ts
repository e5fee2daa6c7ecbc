/**
 * Coalesces jog moves: per servo, at most one move per `intervalMs`. The first request after a
 * quiet spell goes out at once; requests inside the interval replace each other, and the latest
 * goes out when the interval ends, so the arm always ends at the slider's last value.
 * The clock and timers are injected, so a unit test drives time itself.
 */

export interface MoveCoalescerOptions {
  /** Shortest time between two moves of one servo, ms (50 = at most 20 per second). */
  intervalMs: number;
}

export const DEFAULT_MOVE_COALESCER_OPTIONS: MoveCoalescerOptions = { intervalMs: 50 };

export interface CoalescerClock {
  now(): number;
  setTimeout(fn: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
}

const browserClock: CoalescerClock = {
  now: () => performance.now(),
  setTimeout: (fn, ms) => setTimeout(fn, ms),
  clearTimeout: (h) => clearTimeout(h as ReturnType<typeof setTimeout>),
};

interface Slot {
  lastSent: number;
  pending: number; // NaN = nothing pending
  timer: unknown;
}

export class MoveCoalescer {
  private readonly opts: MoveCoalescerOptions;
  private readonly slots = new Map<number, Slot>();

  constructor(
    private readonly send: (id: number, pwm: number) => void,
    opts: Partial<MoveCoalescerOptions> = {},
    private readonly clock: CoalescerClock = browserClock,
  ) {
    this.opts = { ...DEFAULT_MOVE_COALESCER_OPTIONS, ...opts };
  }

  /** Asks for servo `id` to go to `pwm`. */
  request(id: number, pwm: number): void {
    let slot = this.slots.get(id);
    if (!slot) this.slots.set(id, (slot = { lastSent: -Infinity, pending: NaN, timer: undefined }));
    const now = this.clock.now();
    const wait = slot.lastSent + this.opts.intervalMs - now;
    if (wait <= 0 && slot.timer === undefined) {
      slot.lastSent = now;
      this.send(id, pwm);
      return;
    }
    slot.pending = pwm;
    if (slot.timer === undefined) {
      const s = slot;
      s.timer = this.clock.setTimeout(() => this.fire(id, s), Math.max(0, wait));
    }
  }

  private fire(id: number, slot: Slot): void {
    slot.timer = undefined;
    if (Number.isNaN(slot.pending)) return;
    const pwm = slot.pending;
    slot.pending = NaN;
    slot.lastSent = this.clock.now();
    this.send(id, pwm);
  }

  /** Moves waiting to go out, by servo (for the Status panel and tests). */
  get pendingCount(): number {
    let n = 0;
    for (const s of this.slots.values()) if (!Number.isNaN(s.pending)) n++;
    return n;
  }

  /** Drops every pending move (the emergency stop must not be followed by a stale jog). */
  cancelAll(): void {
    for (const slot of this.slots.values()) {
      if (slot.timer !== undefined) this.clock.clearTimeout(slot.timer);
      slot.timer = undefined;
      slot.pending = NaN;
    }
  }
}
