/**
 * One camera's frames and viewers, pure: what the encoder produced last (the latest JPEG; the
 * H.264 group of pictures since the last key frame) and a `Fanout` per kind. Each frame is
 * wrapped for the wire once — a multipart part for MJPEG, a header + access unit for `h264-ws`
 * (./wire.ts) — and the same bytes go to every viewer.
 */
import type { CameraKind } from './announcement.ts';
import { Fanout, type FanoutStats, type FrameSink, type Viewer } from './fanout.ts';
import { encodeH264Header, FLAG_REPLAY, H264_WS_HEADER_BYTES } from './wire.ts';
import { MJPEG_BOUNDARY } from './multipart-parser.ts';

export const MJPEG_CONTENT_TYPE = `multipart/x-mixed-replace; boundary=${MJPEG_BOUNDARY}`;

export interface CameraFeedOptions {
  /** Live frames queued per MJPEG viewer (each stands alone: the newest is all that matters). */
  mjpegQueue: number;
  /** Live frames queued per H.264 viewer before it skips to the next key frame. */
  h264Queue: number;
  /** Viewers per kind at most. */
  maxViewers: number;
  /** Most frames kept for a new H.264 viewer; a longer group of pictures is not replayed. */
  maxReplayFrames: number;
}

export const DEFAULT_CAMERA_FEED_OPTIONS: CameraFeedOptions = {
  mjpegQueue: 2,
  h264Queue: 8,
  maxViewers: 16,
  maxReplayFrames: 90,
};

export interface KindStats extends FanoutStats {
  bytesIn: number;
  /** Capture time (epoch ms) of the last frame from the encoder, or null. */
  lastFrameAt: number | null;
}

interface Wrapped {
  data: Uint8Array;
  key: boolean;
}

const encoder = new TextEncoder();

/** One JPEG as a part of the multipart response, boundary first (so a new part ends the last). */
export function mjpegPart(jpeg: Uint8Array, timestampMs: number, seq: number): Uint8Array {
  const head = encoder.encode(
    `--${MJPEG_BOUNDARY}\r\nContent-Type: image/jpeg\r\nContent-Length: ${jpeg.length}\r\n` +
      `X-Timestamp: ${timestampMs}\r\nX-Sequence: ${seq}\r\n\r\n`,
  );
  const out = new Uint8Array(head.length + jpeg.length + 2);
  out.set(head, 0);
  out.set(jpeg, head.length);
  out.set([13, 10], head.length + jpeg.length);
  return out;
}

export class CameraFeed {
  private readonly o: CameraFeedOptions;
  private readonly fanouts: Record<CameraKind, Fanout>;
  private readonly counts: Record<CameraKind, { bytesIn: number; lastFrameAt: number | null }> = {
    mjpeg: { bytesIn: 0, lastFrameAt: null },
    'h264-ws': { bytesIn: 0, lastFrameAt: null },
  };
  private latestJpeg: { part: Uint8Array; jpeg: Uint8Array; at: number } | null = null;
  private gop: Wrapped[] = [];
  private seq = { mjpeg: 0, h264: 0 };

  constructor(options: Partial<CameraFeedOptions> = {}) {
    this.o = { ...DEFAULT_CAMERA_FEED_OPTIONS, ...options };
    const fanout = (policy: 'latest' | 'until-key', capacity: number) =>
      new Fanout({ policy, capacity, maxViewers: this.o.maxViewers });
    this.fanouts = {
      mjpeg: fanout('latest', this.o.mjpegQueue),
      'h264-ws': fanout('until-key', this.o.h264Queue),
    };
  }

  /** The last JPEG and when it came (for a snapshot), or null. */
  get snapshot(): { jpeg: Uint8Array; at: number } | null {
    return this.latestJpeg;
  }

  /** A JPEG from the encoder. */
  jpeg(jpeg: Uint8Array, timestampMs: number): void {
    const part = mjpegPart(jpeg, timestampMs, this.seq.mjpeg++);
    this.latestJpeg = { part, jpeg, at: timestampMs };
    this.count('mjpeg', jpeg.length, timestampMs);
    this.fanouts.mjpeg.publish(part, true);
  }

  /** An H.264 access unit (Annex B; a key frame carries its SPS and PPS). */
  accessUnit(au: Uint8Array, key: boolean, timestampMs: number): void {
    const header = encodeH264Header({ key, replay: false, timestampMs, seq: this.seq.h264++ });
    const data = new Uint8Array(H264_WS_HEADER_BYTES + au.length);
    data.set(header, 0);
    data.set(au, H264_WS_HEADER_BYTES);
    if (key) this.gop = [];
    if (this.gop.length < this.o.maxReplayFrames && (key || this.gop.length > 0))
      this.gop.push({ data, key });
    else this.gop = [];
    this.count('h264-ws', au.length, timestampMs);
    this.fanouts['h264-ws'].publish(data, key);
  }

  /** The encoder started over: no replay of the old stream; H.264 viewers wait for a key frame. */
  encoderRestarted(): void {
    this.gop = [];
    this.fanouts['h264-ws'].restart();
  }

  /** A new MJPEG viewer: it gets the latest picture at once, then each new one. */
  watchMjpeg(sink: FrameSink, remote: string, now: number): Viewer | null {
    const initial = this.latestJpeg ? [{ data: this.latestJpeg.part, key: true }] : [];
    return this.fanouts.mjpeg.add(sink, remote, now, initial);
  }

  /** A new H.264 viewer: the current group of pictures first (flagged replay), then live. */
  watchH264(sink: FrameSink, remote: string, now: number): Viewer | null {
    const initial = this.gop.map((f) => {
      const copy = f.data.slice();
      copy[1] = copy[1]! | FLAG_REPLAY;
      return { data: copy, key: f.key };
    });
    return this.fanouts['h264-ws'].add(sink, remote, now, initial);
  }

  unwatch(kind: CameraKind, viewer: Viewer): void {
    this.fanouts[kind].remove(viewer);
  }

  viewerCount(kind: CameraKind): number {
    return this.fanouts[kind].viewerCount;
  }

  /** Whether a new viewer of this kind would be refused. */
  full(kind: CameraKind): boolean {
    return this.fanouts[kind].viewerCount >= this.o.maxViewers;
  }

  stats(): Record<CameraKind, KindStats> {
    return {
      mjpeg: { ...this.fanouts.mjpeg.stats(), ...this.counts.mjpeg },
      'h264-ws': { ...this.fanouts['h264-ws'].stats(), ...this.counts['h264-ws'] },
    };
  }

  private count(kind: CameraKind, bytes: number, at: number): void {
    this.counts[kind].bytesIn += bytes;
    this.counts[kind].lastFrameAt = at;
  }
}
