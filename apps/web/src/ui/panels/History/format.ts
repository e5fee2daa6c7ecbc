/** Times and numbers as the History panel writes them (local time). Pure. */

const p2 = (n: number) => String(n).padStart(2, '0');

/** Epoch ms → `HH:MM:SS`, local time. */
export function clockTime(ms: number): string {
  const d = new Date(ms);
  return `${p2(d.getHours())}:${p2(d.getMinutes())}:${p2(d.getSeconds())}`;
}

/** Epoch ms → `YYYY-MM-DD HH:MM:SS`, local time. */
export function dateTime(ms: number): string {
  const d = new Date(ms);
  return `${d.getFullYear()}-${p2(d.getMonth() + 1)}-${p2(d.getDate())} ${clockTime(ms)}`;
}

/** A time for a table: the clock alone within a day of `ref`, else with the date. */
export function tableTime(ms: number, ref: number): string {
  return Math.abs(ms - ref) < 86_400_000 ? clockTime(ms) : dateTime(ms);
}

/** `1.23` or an em dash for null. */
export function fixed(v: number | null | undefined, digits = 2): string {
  return v === null || v === undefined || !Number.isFinite(v) ? '—' : v.toFixed(digits);
}
