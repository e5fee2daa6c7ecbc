/**
 * A replayed camera's segments, each fetched whole (with the page's login) and held while it is
 * needed: asking for the segment the replay is in also starts the fetch of the one after it, so
 * it is already there when playback crosses the boundary. At most those two are held (one
 * ahead); the others are let go. A fetch that fails is forgotten, so the next ask tries again.
 */
import type { RecordedSegment } from './videoAt.ts';

export class SegmentsAhead<T> {
  private readonly held = new Map<string, Promise<T>>();

  constructor(
    /** One segment's bytes by name (e.g. ui/panels/History/cameraSegmentsApi.ts's fetchSegment). */
    private readonly load: (name: string) => Promise<T>,
  ) {}

  /** The segment `name` of `segments` (in time order), the next one's fetch started. */
  get(segments: readonly RecordedSegment[], name: string): Promise<T> {
    const i = segments.findIndex((s) => s.name === name);
    const next = i >= 0 ? segments[i + 1]?.name : undefined;
    const keep = next && next !== name ? [name, next] : [name];
    for (const held of [...this.held.keys()]) if (!keep.includes(held)) this.held.delete(held);
    for (const k of keep) if (!this.held.has(k)) this.held.set(k, this.fetch(k));
    return this.held.get(name)!;
  }

  /** The names held now (fetched or on the way). */
  names(): string[] {
    return [...this.held.keys()];
  }

  private fetch(name: string): Promise<T> {
    const p = this.load(name);
    // a failed fetch is told to whoever asks for it; held, it would be the answer for good
    p.catch(() => {
      if (this.held.get(name) === p) this.held.delete(name);
    });
    return p;
  }
}
