/**
 * One take of an MJPEG-only camera → `.mjpeg` segments, without ffmpeg and without re-encoding:
 * each JPEG is written as it was served, as one part of a `multipart/x-mixed-replace` file
 * (`@armtwin/camera`'s `mjpegPart`: `Content-Length`, `X-Timestamp` = the frame's epoch ms),
 * the same bytes a viewer of the camera server reads, so the page's multipart reader and
 * ffmpeg's `mpjpeg` demuxer read it back. A segment is cut at the first frame `segmentS` after
 * its first; it is written as `<baseMs>-<n>.part` and renamed to its times
 * (./segment-files.ts) once closed, with the closing boundary, so a file with a final name is
 * always whole. Its end is the next frame's time (the last frame shows until then), or, for the
 * take's last segment, its last frame plus the frame interval before it.
 */
import fs from 'node:fs';
import path from 'node:path';
import { MJPEG_BOUNDARY, mjpegPart } from '@armtwin/camera';
import { PART_EXT, segmentName, type Segment } from './segment-files.ts';

export interface JpegSegmenterOptions {
  dir: string;
  segmentS: number;
  /** Epoch ms of the take's first frame (names its `.part` files). */
  baseMs: number;
  onSegment(segment: Pick<Segment, 'name' | 'startMs' | 'endMs' | 'bytes'>): void;
  /** A problem, by kind: `write-failed`. */
  onProblem(kind: string, message: string): void;
}

const CLOSE = new TextEncoder().encode(`--${MJPEG_BOUNDARY}--\r\n`);

export class JpegSegmenter {
  private open: {
    fd: number;
    part: string;
    startMs: number;
    lastMs: number;
    stepMs: number;
    frames: number;
  } | null = null;
  private count = 0;
  private failed = false;

  constructor(private readonly o: JpegSegmenterOptions) {
    fs.mkdirSync(o.dir, { recursive: true });
  }

  /** One JPEG of the take, at `atMs` (epoch ms, after the one before). */
  write(jpeg: Uint8Array, atMs: number): void {
    if (this.failed) return;
    try {
      const s = this.open;
      if (s && atMs - s.startMs >= this.o.segmentS * 1000) this.close(atMs);
      const cur = this.open ?? this.start(atMs);
      fs.writeSync(cur.fd, mjpegPart(jpeg, atMs, cur.frames++));
      if (cur.frames > 1) cur.stepMs = atMs - cur.lastMs;
      cur.lastMs = atMs;
    } catch (err) {
      this.failed = true;
      this.o.onProblem('write-failed', (err as Error).message);
      this.discard();
    }
  }

  /** Ends the take: its last segment is closed and renamed. */
  async end(): Promise<void> {
    if (this.failed || !this.open) return;
    try {
      this.close(this.open.lastMs + Math.max(1, this.open.stepMs));
    } catch (err) {
      this.o.onProblem('write-failed', (err as Error).message);
      this.discard();
    }
  }

  private start(atMs: number) {
    const part = path.join(this.o.dir, `${this.o.baseMs}-${this.count++}${PART_EXT}`);
    const fd = fs.openSync(part, 'w');
    this.open = { fd, part, startMs: atMs, lastMs: atMs, stepMs: 0, frames: 0 };
    return this.open;
  }

  private close(endMs: number): void {
    const s = this.open!;
    this.open = null;
    fs.writeSync(s.fd, CLOSE);
    fs.closeSync(s.fd);
    const name = segmentName(s.startMs, endMs, 'mjpeg');
    fs.renameSync(s.part, path.join(this.o.dir, name));
    const { size } = fs.statSync(path.join(this.o.dir, name));
    this.o.onSegment({ name, startMs: s.startMs, endMs, bytes: size });
  }

  private discard(): void {
    const s = this.open;
    this.open = null;
    if (!s) return;
    try {
      fs.closeSync(s.fd);
    } catch {
      // closed already
    }
    fs.rmSync(s.part, { force: true });
  }
}
