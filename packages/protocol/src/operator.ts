/**
 * The operator's hold on an arm: `arm/{id}/operator` (PROTOCOL.md §3), retained `1` while an
 * operator holds control, `0` (also its last will) when it lets go or drops.
 *
 * armtwin adds a lease on top, so that a dropped operator does not wait for the broker to
 * notice a dead connection (Mosquitto 2.0 checks keep-alives on a coarse timer and publishes a
 * will seconds late). An operator that repeats `1` every `OPERATOR_BEAT_MS` is *beating*; a
 * controller that has seen a repeated `1` treats `OPERATOR_LEASE_MS` without another one as a
 * `0`. A holder that publishes `1` once (a script, `mosquitto_pub -r`) is never timed out, so
 * the contract's plain `1`/`0` clients behave exactly as before. See docs/protocol.md.
 */

/** How often the HUD repeats its retained `1` while it holds an arm. */
export const OPERATOR_BEAT_MS = 500;
/**
 * How long a controller waits for the next `1` from a beating operator before it lets go for
 * it: five beats, and under 1.5 × the HUD's 2 s deadman keep-alive.
 */
export const OPERATOR_LEASE_MS = 2500;

export type OperatorSignal = 'hold' | 'release';

const decoder = new TextDecoder();

/** `1` → hold, `0` → release (surrounding whitespace ignored); anything else → null. */
export function parseOperator(payload: Uint8Array | string): OperatorSignal | null {
  const text = (typeof payload === 'string' ? payload : decoder.decode(payload)).trim();
  return text === '1' ? 'hold' : text === '0' ? 'release' : null;
}

/** Why a watch let go: a `0` arrived, or a beating operator's lease ran out. */
export type LetGoReason = 'released' | 'lapsed';

export interface OperatorTimers {
  setTimeout(fn: () => void, ms: number): unknown;
  clearTimeout(handle: unknown): void;
}

/**
 * What a controller knows of its operator. `none`: nobody holds the arm (or nobody has said
 * so); `held`: a `1` arrived; `beating`: a `1` arrived while already held, so the lease runs.
 */
export type OperatorState = 'none' | 'held' | 'beating';

/** The controller side of the lease. Pure: the timers are injected. */
export class OperatorWatch {
  state: OperatorState = 'none';
  readonly counters = { holds: 0, releases: 0, lapses: 0, ignored: 0 };
  private timer: unknown;

  /** `leaseMs` 0 turns the lease off: only a `0` lets go. */
  constructor(
    private readonly timers: OperatorTimers,
    private readonly onLetGo: (reason: LetGoReason) => void,
    readonly leaseMs: number = OPERATOR_LEASE_MS,
  ) {}

  receive(payload: Uint8Array | string): void {
    const signal = parseOperator(payload);
    if (signal === null) {
      this.counters.ignored++;
      return;
    }
    if (signal === 'release') return this.letGo('released');
    this.counters.holds++;
    if (this.state === 'none') {
      this.state = 'held';
      return;
    }
    this.state = 'beating';
    if (this.leaseMs <= 0) return;
    this.clear();
    this.timer = this.timers.setTimeout(() => {
      this.timer = undefined;
      this.letGo('lapsed');
    }, this.leaseMs);
  }

  /** Forget the operator without acting (the controller disconnects; a retained value follows). */
  reset(): void {
    this.clear();
    this.state = 'none';
  }

  private letGo(reason: LetGoReason): void {
    this.clear();
    this.state = 'none';
    this.counters[reason === 'released' ? 'releases' : 'lapses']++;
    this.onLetGo(reason);
  }

  private clear(): void {
    if (this.timer !== undefined) this.timers.clearTimeout(this.timer);
    this.timer = undefined;
  }
}
