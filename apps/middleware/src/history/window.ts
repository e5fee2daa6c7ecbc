/**
 * Window sizing for downsampled series: the smallest "sensible" duration (1-2-5 steps, then
 * clock steps) whose windows, aligned to the epoch as Flux aligns them, cut [start, stop)
 * into at most `maxPoints` pieces. Pure.
 */

/** Candidate window lengths, ms, ascending, each with its Flux duration literal text. */
export const WINDOW_LADDER: readonly { ms: number; text: string }[] = [
  [1, '1ms'],
  [2, '2ms'],
  [5, '5ms'],
  [10, '10ms'],
  [20, '20ms'],
  [50, '50ms'],
  [100, '100ms'],
  [200, '200ms'],
  [500, '500ms'],
  [1_000, '1s'],
  [2_000, '2s'],
  [5_000, '5s'],
  [10_000, '10s'],
  [15_000, '15s'],
  [30_000, '30s'],
  [60_000, '1m'],
  [120_000, '2m'],
  [300_000, '5m'],
  [600_000, '10m'],
  [900_000, '15m'],
  [1_800_000, '30m'],
  [3_600_000, '1h'],
  [7_200_000, '2h'],
  [10_800_000, '3h'],
  [21_600_000, '6h'],
  [43_200_000, '12h'],
  [86_400_000, '1d'],
  [604_800_000, '7d'],
].map(([ms, text]) => ({ ms: ms as number, text: text as string }));

/** How many epoch-aligned windows of `every` ms touch [start, stop). */
export function windowCount(startMs: number, stopMs: number, everyMs: number): number {
  return Math.ceil(stopMs / everyMs) - Math.floor(startMs / everyMs);
}

/**
 * The window for a range: the first ladder step giving ≤ maxPoints windows. Falls back to the
 * largest step (only reachable with spans far beyond the API's 31-day limit).
 */
export function windowFor(
  startMs: number,
  stopMs: number,
  maxPoints: number,
): { ms: number; text: string } {
  for (const w of WINDOW_LADDER) {
    if (windowCount(startMs, stopMs, w.ms) <= maxPoints) return w;
  }
  return WINDOW_LADDER[WINDOW_LADDER.length - 1]!;
}
