/**
 * Hold-to-jog arithmetic (pure). While a joint is held, the page sends a keep-alive every
 * `keepAliveMs`: a move to a target only `horizonMs` of travel ahead of where the joint is, in
 * `horizonMs`. If keep-alives stop (the page stalls, the tab freezes, the network goes), the arm
 * reaches the last short target and stops there by itself. The contract: docs/protocol.md
 * § Hold-to-jog.
 */

export interface HoldJogOptions {
  /** Time between two keep-alives of a held joint, ms. */
  keepAliveMs: number;
  /** How far ahead each keep-alive aims, as travel time at the chosen speed; also its `T`, ms. */
  horizonMs: number;
  /** Speeds offered, joint units per second (° for a revolute joint, mm for a prismatic one). */
  speeds: readonly number[];
  /** The speed a page starts with. */
  speed: number;
  /**
   * The most one keep-alive of the tip may turn a joint (° or mm): more means the IK chose a
   * pose far from the arm's (another elbow branch, a singularity), and the tip hold stops.
   */
  maxTipJointStep: number;
}

export const DEFAULT_HOLD_JOG_OPTIONS: HoldJogOptions = {
  keepAliveMs: 100,
  horizonMs: 250,
  speeds: [5, 15, 30, 60],
  speed: 15,
  maxTipJointStep: 10,
};

/**
 * The joint value one keep-alive aims at: `rate` (−1 … 1, the direction and how far a stick is
 * pushed) × `speed` (units/s) × the horizon ahead of `live`, clamped to the joint's limits.
 * NaN when `live` is unknown (nothing is then sent).
 */
export function holdTarget(
  live: number,
  rate: number,
  speed: number,
  horizonMs: number,
  min: number,
  max: number,
): number {
  if (!Number.isFinite(live) || !Number.isFinite(rate)) return NaN;
  const r = Math.max(-1, Math.min(1, rate));
  const to = live + (r * speed * horizonMs) / 1000;
  return Math.max(min, Math.min(max, to));
}

/** The combined rate of several inputs on one joint (a key and a stick), within −1 … 1. */
export function combinedRate(rates: Iterable<number>): number {
  let sum = 0;
  for (const r of rates) if (Number.isFinite(r)) sum += r;
  return Math.max(-1, Math.min(1, sum));
}

/** Hold keys: joint i moves − with `minus[i]` and + with `plus[i]` (KeyboardEvent.code). */
export interface HoldKeys {
  readonly plus: readonly string[];
  readonly minus: readonly string[];
}

/** Q/A, W/S, E/D, R/F, T/G, Y/H, U/J: the upper row +, the row under it −, one column a joint. */
export const DEFAULT_HOLD_KEYS: HoldKeys = {
  plus: ['KeyQ', 'KeyW', 'KeyE', 'KeyR', 'KeyT', 'KeyY', 'KeyU'],
  minus: ['KeyA', 'KeyS', 'KeyD', 'KeyF', 'KeyG', 'KeyH', 'KeyJ'],
};

/** Joint index and direction of a key (KeyboardEvent.code), or null. */
export function keyHold(keys: HoldKeys, code: string): { index: number; rate: 1 | -1 } | null {
  const p = keys.plus.indexOf(code);
  if (p >= 0) return { index: p, rate: 1 };
  const m = keys.minus.indexOf(code);
  if (m >= 0) return { index: m, rate: -1 };
  return null;
}

/** `KeyQ` → `Q` (for the on-screen list). */
export const keyLabel = (code: string): string => code.replace(/^Key|^Digit/, '');
