/**
 * A client of the middleware's history API: `GET <base>/history/<endpoint>?arm=&id=&…` → JSON.
 * Never throws: every failure becomes text for the panel (a 400 names its parameter, a 503
 * says history needs storage, an unreachable API says so). `fetch` and extra headers (a login
 * may add `Authorization`) are injected.
 */
import type { Loaded } from './loaded.ts';

export type Endpoint =
  'series' | 'alarms' | 'tracking' | 'pose' | 'audit' | 'export' | 'thermal-model';
export type Fetch = (url: string, init?: RequestInit) => Promise<Response>;

export interface HistoryApiOptions {
  /** Base URL of the API, e.g. `http://host/api` or `/api`. */
  base: string;
  fetch?: Fetch;
  /** Extra request headers. */
  headers?: Record<string, string>;
}

/** `<base>/history/<endpoint>?<params>`; array values become repeated parameters. */
export function historyUrl(
  base: string,
  endpoint: Endpoint,
  params: Record<string, string | number | readonly string[]>,
): string {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(params)) {
    if (Array.isArray(v)) for (const item of v) q.append(k, String(item));
    else q.set(k, String(v));
  }
  return `${base.replace(/\/+$/, '')}/history/${endpoint}?${q.toString()}`;
}

/** The text shown for a non-2xx answer (`body` is the parsed JSON, or the raw text). */
export function errorText(status: number, body: unknown): string {
  const obj = typeof body === 'object' && body !== null ? (body as Record<string, unknown>) : {};
  const error = typeof obj.error === 'string' ? obj.error : '';
  const parameter = typeof obj.parameter === 'string' ? obj.parameter : '';
  if (status === 400)
    return `The history API refused the request${parameter ? ` (parameter ${parameter})` : ''}: ${error || 'bad request'}`;
  if (status === 503)
    return `History is not available: ${error || 'the API has no storage'} (HTTP 503).`;
  if (status === 502) return `The history database failed: ${error || 'bad gateway'} (HTTP 502).`;
  if (status === 401)
    return `The history API needs a login: ${error || 'unauthorised'} (HTTP 401).`;
  if (status === 404)
    return `No history API at this address (HTTP 404)${error ? `: ${error}` : ''}. Is the middleware running?`;
  return `The history API answered HTTP ${status}${error ? `: ${error}` : ''}.`;
}

export class HistoryApi {
  private readonly fetch: Fetch;

  constructor(private readonly opts: HistoryApiOptions) {
    this.fetch = opts.fetch ?? ((url, init) => globalThis.fetch(url, init));
  }

  async get<T>(
    endpoint: Endpoint,
    params: Record<string, string | number | readonly string[]>,
    signal?: AbortSignal,
  ): Promise<Loaded<T>> {
    const url = historyUrl(this.opts.base, endpoint, params);
    let res: Response;
    try {
      res = await this.fetch(url, {
        headers: { accept: 'application/json', ...this.opts.headers },
        signal,
      });
    } catch (err) {
      if (signal?.aborted) return { ok: false, error: 'Cancelled.' };
      const why = err instanceof Error ? err.message : String(err);
      return { ok: false, error: `The history API at ${this.opts.base} is unreachable: ${why}` };
    }
    const text = await res.text().catch(() => '');
    let body: unknown = text;
    try {
      body = JSON.parse(text);
    } catch {
      // not JSON: keep the text
    }
    if (!res.ok) return { ok: false, error: errorText(res.status, body) };
    if (typeof body !== 'object' || body === null)
      return { ok: false, error: `The history API sent something that is not JSON (${url}).` };
    return { ok: true, data: body as T };
  }

  /** A file endpoint (`export`): the body and the file name the server gives it. */
  async file(
    endpoint: Endpoint,
    params: Record<string, string | number | readonly string[]>,
  ): Promise<Loaded<{ blob: Blob; name: string }>> {
    const url = historyUrl(this.opts.base, endpoint, params);
    try {
      const res = await this.fetch(url, { headers: { ...this.opts.headers } });
      if (!res.ok) {
        const text = await res.text().catch(() => '');
        let body: unknown = text;
        try {
          body = JSON.parse(text);
        } catch {
          // not JSON: keep the text
        }
        return { ok: false, error: errorText(res.status, body) };
      }
      const name = /filename="([^"]+)"/.exec(res.headers.get('content-disposition') ?? '')?.[1];
      return { ok: true, data: { blob: await res.blob(), name: name ?? `${endpoint}.bin` } };
    } catch (err) {
      const why = err instanceof Error ? err.message : String(err);
      return { ok: false, error: `The history API at ${this.opts.base} is unreachable: ${why}` };
    }
  }
}
