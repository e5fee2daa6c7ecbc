/**
 * Broker connection gaps, for the Status panel: when the connection was lost, and once it is
 * back, how long the gap was (shown for `showForMs`). Pure: every method takes `now`, epoch ms.
 * The first connection is not a gap; nor is a deliberate stop.
 */
export interface GapTrackerOptions {
  /** How long "reconnected; gap of N s" stays up, ms. */
  showForMs: number;
}

export const DEFAULT_GAP_TRACKER_OPTIONS: GapTrackerOptions = { showForMs: 30_000 };

export type GapView =
  | { kind: 'none' }
  | { kind: 'down'; since: number }
  | { kind: 'recovered'; gapMs: number; at: number };

export class GapTracker {
  readonly opts: GapTrackerOptions;
  private everConnected = false;
  private connected = false;
  /** When the current gap began (NaN = none). */
  private lostAt = NaN;
  private lastGapMs = NaN;
  private restoredAt = NaN;
  /** Gaps seen, for the debug hook and tests. */
  gaps = 0;

  constructor(opts: Partial<GapTrackerOptions> = {}) {
    this.opts = { ...DEFAULT_GAP_TRACKER_OPTIONS, ...opts };
  }

  /** The connection is up. Returns the gap it ends, ms, or null. */
  restored(now: number): number | null {
    this.everConnected = this.connected = true;
    if (Number.isNaN(this.lostAt)) return null;
    this.lastGapMs = Math.max(0, now - this.lostAt);
    this.restoredAt = now;
    this.lostAt = NaN;
    return this.lastGapMs;
  }

  /** The connection went down (any event: close, offline, error). True if a gap starts now. */
  lost(now: number): boolean {
    if (!this.connected) return false;
    this.connected = false;
    if (!this.everConnected) return false;
    this.lostAt = now;
    this.gaps++;
    return true;
  }

  view(now: number): GapView {
    if (!Number.isNaN(this.lostAt)) return { kind: 'down', since: this.lostAt };
    if (!Number.isNaN(this.restoredAt) && now - this.restoredAt < this.opts.showForMs)
      return { kind: 'recovered', gapMs: this.lastGapMs, at: this.restoredAt };
    return { kind: 'none' };
  }
}

/** Epoch ms → local "HH:MM:SS". */
export function clockTime(ms: number): string {
  const d = new Date(ms);
  const p = (n: number) => String(n).padStart(2, '0');
  return `${p(d.getHours())}:${p(d.getMinutes())}:${p(d.getSeconds())}`;
}

/** What the Status panel says about the broker connection's gaps ('' = nothing to say). */
export function gapWords(v: GapView): string {
  if (v.kind === 'down') return `broker disconnected since ${clockTime(v.since)} — reconnecting`;
  if (v.kind === 'recovered') {
    const s = v.gapMs / 1000;
    return `reconnected; gap of ${s < 10 ? s.toFixed(1) : Math.round(s)} s`;
  }
  return '';
}
