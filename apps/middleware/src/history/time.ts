/**
 * Time parameters: `now`, relative (`-90s`, `-5m`, `-1h`, `-24h`, `-7d`, `-2w`, `-500ms`),
 * epoch milliseconds (`1700000000000`) or RFC 3339 (`2023-11-14T22:13:20Z`,
 * `2023-11-14T23:13:20.5+01:00`; fractions past the millisecond are cut). Pure: the clock
 * is an argument.
 */

/** Earliest and latest accepted instants, ms (Flux's time is int64 ns: up to 2262). */
export const MIN_TIME_MS = 0;
export const MAX_TIME_MS = Date.UTC(2200, 0, 1);

const UNIT_MS: Record<string, number> = {
  ms: 1,
  s: 1000,
  m: 60_000,
  h: 3_600_000,
  d: 86_400_000,
  w: 604_800_000,
};

const RELATIVE = /^-(\d{1,9})(ms|s|m|h|d|w)$/;
const EPOCH_MS = /^\d{1,16}$/;
const RFC3339 =
  /^(\d{4})-(\d{2})-(\d{2})[Tt](\d{2}):(\d{2}):(\d{2})(?:\.(\d{1,9}))?(?:([Zz])|([+-])(\d{2}):(\d{2}))$/;

/** RFC 3339 → epoch ms, or undefined when malformed or not a real calendar instant. */
export function parseRfc3339(text: string): number | undefined {
  const m = RFC3339.exec(text);
  if (!m) return undefined;
  const [y, mo, d, h, mi, s] = m.slice(1, 7).map(Number) as [
    number,
    number,
    number,
    number,
    number,
    number,
  ];
  const frac = m[7] ? Number(m[7].slice(0, 3).padEnd(3, '0')) : 0;
  const base = Date.UTC(y, mo - 1, d, h, mi, s, frac);
  const check = new Date(base);
  if (
    check.getUTCFullYear() !== y ||
    check.getUTCMonth() !== mo - 1 ||
    check.getUTCDate() !== d ||
    check.getUTCHours() !== h ||
    check.getUTCMinutes() !== mi ||
    check.getUTCSeconds() !== s
  ) {
    return undefined;
  }
  if (m[8]) return base;
  const offH = Number(m[10]);
  const offM = Number(m[11]);
  if (offH > 23 || offM > 59) return undefined;
  const sign = m[9] === '-' ? -1 : 1;
  return base - sign * (offH * 60 + offM) * 60_000;
}

/** Any accepted time form → epoch ms, or undefined. `nowMs` resolves `now` and relatives. */
export function parseTime(text: string, nowMs: number): number | undefined {
  let t: number | undefined;
  if (text === 'now') t = nowMs;
  else if (RELATIVE.test(text)) {
    const [, n, unit] = RELATIVE.exec(text)!;
    t = nowMs - Number(n) * UNIT_MS[unit!]!;
  } else if (EPOCH_MS.test(text)) t = Number(text);
  else t = parseRfc3339(text);
  if (t === undefined || !Number.isSafeInteger(t) || t < MIN_TIME_MS || t > MAX_TIME_MS)
    return undefined;
  return t;
}
