/**
 * The middleware's recorded camera segments (docs/cameras-recording.md):
 * `GET <base>/arms/{arm}/cameras/{cam}/segments?from=&to=` lists those holding any frame of a
 * range; `…/segments/{name}` is one MP4, what the replay's <video> plays. Never throws: a
 * failure becomes text for the panel.
 */
import type { RecordedSegment } from '../../../core/replay/videoAt.ts';
import type { Fetch } from './historyApi.ts';
import type { Loaded } from './loaded.ts';
import type { TimeRange } from './range.ts';

const camBase = (base: string, arm: string, cam: string) =>
  `${base.replace(/\/+$/, '')}/arms/${encodeURIComponent(arm)}/cameras/${encodeURIComponent(cam)}/segments`;

/** The URL of one segment's MP4. */
export function segmentUrl(base: string, arm: string, cam: string, name: string): string {
  return `${camBase(base, arm, cam)}/${encodeURIComponent(name)}`;
}

/** The segments of `cam` holding any frame of `range`, by time. */
export async function listSegments(
  o: { base: string; headers?: Record<string, string>; fetch?: Fetch },
  arm: string,
  cam: string,
  range: TimeRange,
): Promise<Loaded<RecordedSegment[]>> {
  const q = new URLSearchParams({
    from: new Date(range.start).toISOString(),
    to: new Date(range.stop).toISOString(),
  });
  const get = o.fetch ?? ((url, init) => globalThis.fetch(url, init));
  try {
    const res = await get(`${camBase(o.base, arm, cam)}?${q.toString()}`, {
      headers: { accept: 'application/json', ...o.headers },
    });
    const body = (await res.json().catch(() => ({}))) as {
      segments?: RecordedSegment[];
      errors?: string[];
    };
    if (!res.ok || !Array.isArray(body.segments))
      return {
        ok: false,
        error: `The camera recordings of ${cam} are not available: ${body.errors?.join('; ') ?? `HTTP ${res.status}`}`,
      };
    return {
      ok: true,
      data: body.segments.map((s) => ({ name: s.name, startMs: s.startMs, endMs: s.endMs })),
    };
  } catch (err) {
    return { ok: false, error: `The camera recordings of ${cam} are unreachable: ${String(err)}` };
  }
}

/**
 * One segment's bytes as a Blob, for a `blob:` URL: the <video> can then seek anywhere in it. The
 * API serves byte ranges too, but a <video> pointed at its URL cannot send the login's header, so
 * the page fetches each segment whole, the next one while the current one plays
 * (core/replay/segmentsAhead.ts).
 */
export async function fetchSegment(
  o: { base: string; headers?: Record<string, string>; fetch?: Fetch },
  arm: string,
  cam: string,
  name: string,
): Promise<Blob> {
  const get = o.fetch ?? ((url, init) => globalThis.fetch(url, init));
  const res = await get(segmentUrl(o.base, arm, cam, name), { headers: { ...o.headers } });
  if (!res.ok) throw new Error(`segment ${name} of ${cam}: HTTP ${res.status}`);
  return res.blob();
}
