/**
 * The camera recordings' folder, pure: `<dir>/<armId>/<camId>/<startMs>-<endMs>.mp4` (H.264) or
 * `….mjpeg` (the JPEGs of an MJPEG-only camera as served: ./jpeg-segmenter.ts), each name the
 * epoch ms of its first frame and of the end of its last (so a folder listing is the time line,
 * sorted by name). A segment is written as `….part` and renamed once it is closed; a `.part` left by a crash is never served and is removed at start. Which segments a time
 * range needs, and which retention deletes (oldest first), are decided here.
 */

/** A segment's file type by what it holds: H.264 in MP4, or JPEGs in a multipart file. */
export const SEGMENT_EXTS = { h264: '.mp4', mjpeg: '.mjpeg' } as const;
export type SegmentKind = keyof typeof SEGMENT_EXTS;
export const PART_EXT = '.part';
/** Epoch ms are written with 13 digits (until the year 2286), so names sort as times. */
const MS_DIGITS = 13;
const NAME = /^(\d{13})-(\d{13})\.(mp4|mjpeg)$/;

/** What a segment holds, by its name. */
export const segmentKind = (name: string): SegmentKind =>
  name.endsWith(SEGMENT_EXTS.mjpeg) ? 'mjpeg' : 'h264';

export interface Segment {
  armId: string;
  camId: string;
  /** The file's name in its camera's folder. */
  name: string;
  /** Epoch ms of the first frame. */
  startMs: number;
  /** Epoch ms of the end of the last frame. */
  endMs: number;
  bytes: number;
}

export function segmentName(startMs: number, endMs: number, kind: SegmentKind = 'h264'): string {
  const pad = (ms: number) => String(Math.round(ms)).padStart(MS_DIGITS, '0');
  if (!(endMs >= startMs) || startMs < 0) throw new RangeError(`bad segment ${startMs}–${endMs}`);
  return `${pad(startMs)}-${pad(endMs)}${SEGMENT_EXTS[kind]}`;
}

/** A finished segment's times from its name, or null for anything else (a `.part`, a stray). */
export function parseSegmentName(name: string): { startMs: number; endMs: number } | null {
  const m = NAME.exec(name);
  if (!m) return null;
  const startMs = Number(m[1]);
  const endMs = Number(m[2]);
  return endMs >= startMs ? { startMs, endMs } : null;
}

/** The segments that hold any frame of [fromMs, toMs], by time. */
export function segmentsBetween<S extends Pick<Segment, 'startMs' | 'endMs'>>(
  segments: readonly S[],
  fromMs: number,
  toMs: number,
): S[] {
  return segments
    .filter((s) => s.endMs >= fromMs && s.startMs <= toMs)
    .sort((a, b) => a.startMs - b.startMs);
}

export interface RetentionOptions {
  /** Segments that ended longer ago than this are deleted, ms; 0 = no age limit. */
  maxAgeMs: number;
  /** The folder's bound, bytes: the oldest segments go until the rest fit; 0 = no bound. */
  maxBytes: number;
}

export interface RetentionPlan<S> {
  /** Oldest first. */
  deletions: { segment: S; why: 'age' | 'size' }[];
  /** Bytes left after the deletions. */
  bytesLeft: number;
}

/**
 * What retention deletes from every camera's segments together: whatever is past the age limit,
 * then the oldest (by end time, over all cameras) until the total is within the bound.
 */
export function retentionPlan<S extends Pick<Segment, 'endMs' | 'bytes'>>(
  segments: readonly S[],
  nowMs: number,
  o: RetentionOptions,
): RetentionPlan<S> {
  const byAge = [...segments].sort((a, b) => a.endMs - b.endMs);
  const deletions: RetentionPlan<S>['deletions'] = [];
  let bytesLeft = byAge.reduce((n, s) => n + s.bytes, 0);
  for (const segment of byAge) {
    const old = o.maxAgeMs > 0 && nowMs - segment.endMs > o.maxAgeMs;
    const over = o.maxBytes > 0 && bytesLeft > o.maxBytes;
    if (!old && !over) break;
    deletions.push({ segment, why: old ? 'age' : 'size' });
    bytesLeft -= segment.bytes;
  }
  return { deletions, bytesLeft };
}
