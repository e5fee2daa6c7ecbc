/** The Cameras panel's words. */

const two = (n: number) => String(n).padStart(2, '0');

/** Local HH:MM:SS. */
export function clockTime(epochMs: number): string {
  const d = new Date(epochMs);
  return `${two(d.getHours())}:${two(d.getMinutes())}:${two(d.getSeconds())}`;
}

export const ageWords = (ms: number): string =>
  `last frame ${(Math.max(0, ms) / 1000).toFixed(1)} s ago`;

export const offlineWords = (sinceMs: number, reason: string): string =>
  `camera offline since ${clockTime(sinceMs)}${reason ? ` (${reason})` : ''}`;
