/** The `?from=&to=` of a GET that lists a time range: ISO 8601 times, each optional. */
import type http from 'node:http';

const time = (v: string | null): number | undefined | null => {
  if (v === null) return undefined;
  const ms = Date.parse(v);
  return /^\d{4}-\d\d-\d\d/.test(v) && Number.isFinite(ms) ? ms : null;
};

/** Epoch ms of `from` and `to` (undefined when absent), or null when either is not a time. */
export function timeRange(
  req: http.IncomingMessage,
): { from: number | undefined; to: number | undefined } | null {
  const q = new URL(req.url ?? '/', 'http://x').searchParams;
  const [from, to] = [time(q.get('from')), time(q.get('to'))];
  return from === null || to === null ? null : { from, to };
}

export const TIME_RANGE_ERROR = 'from and to are ISO 8601 times';
