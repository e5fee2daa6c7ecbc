/**
 * A client of the middleware's episodes route (`<base>/arms/<arm>/episodes`, docs/dataset.md):
 * list an arm's episodes, and start, stop, discard or cut one. Never throws: a failure becomes
 * the text the panel shows (the route's own `errors`, else the history API's wording).
 */
import type { EpisodeActionAnswer, EpisodeMark, EpisodesAnswer } from '@armtwin/api';
import { errorText, type HistoryApiOptions } from './historyApi.ts';
import type { Loaded } from './loaded.ts';

export type EpisodeRequest =
  | { action: 'start'; task: string }
  | { action: 'stop' }
  | { action: 'discard'; start?: number }
  | { action: 'cut'; task: string; from: number; to: number };

/** The route's first error, else the history API's wording of the status. */
function failure(status: number, body: unknown): string {
  const errors = (body as { errors?: unknown } | null)?.errors;
  if (Array.isArray(errors) && typeof errors[0] === 'string')
    return `Refused (HTTP ${status}): ${errors[0]}`;
  return errorText(status, body);
}

export class EpisodesApi {
  constructor(private readonly opts: HistoryApiOptions) {}

  private async call<T>(arm: string, init: RequestInit): Promise<Loaded<T>> {
    const url = `${this.opts.base.replace(/\/+$/, '')}/arms/${encodeURIComponent(arm)}/episodes`;
    const fetch = this.opts.fetch ?? ((u: string, i?: RequestInit) => globalThis.fetch(u, i));
    try {
      const res = await fetch(url, {
        ...init,
        headers: { accept: 'application/json', ...this.opts.headers, ...init.headers },
      });
      const text = await res.text();
      let body: unknown = text;
      try {
        body = JSON.parse(text);
      } catch {
        // not JSON: keep the text
      }
      return res.ok
        ? { ok: true, data: body as T }
        : { ok: false, error: failure(res.status, body) };
    } catch (err) {
      const why = err instanceof Error ? err.message : String(err);
      return { ok: false, error: `The episodes API at ${this.opts.base} is unreachable: ${why}` };
    }
  }

  async list(arm: string): Promise<Loaded<EpisodeMark[]>> {
    const r = await this.call<EpisodesAnswer>(arm, { method: 'GET' });
    return r.ok ? { ok: true, data: r.data.episodes } : r;
  }

  async act(arm: string, request: EpisodeRequest): Promise<Loaded<EpisodeMark>> {
    const r = await this.call<EpisodeActionAnswer>(arm, {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(request),
    });
    if (!r.ok) return r;
    return r.data.ok ? { ok: true, data: r.data.episode } : { ok: false, error: r.data.errors[0]! };
  }
}

/** `m:ss` (or `h:mm:ss`) of a duration in ms. Pure. */
export function elapsed(ms: number): string {
  const s = Math.max(0, Math.floor(ms / 1000));
  const p2 = (n: number) => String(n).padStart(2, '0');
  const h = Math.floor(s / 3600);
  const m = Math.floor((s % 3600) / 60);
  return h > 0 ? `${h}:${p2(m)}:${p2(s % 60)}` : `${m}:${p2(s % 60)}`;
}
