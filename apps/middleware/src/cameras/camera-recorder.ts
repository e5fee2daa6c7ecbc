/**
 * Records one camera: a viewer of its `h264-ws` feed (`@armtwin/camera`'s wire), like a HUD,
 * that hands the frames ./takes.ts keeps to a ./segmenter.ts ffmpeg per take. The connection is
 * opened again after a back-off whenever it drops (the camera server restarted); each drop is
 * one gap. The frames are the ones the server sends every viewer: nothing is decoded or encoded.
 */
import { WebSocket } from 'ws';
import { decodeH264Message, flvFrame, flvStart } from '@armtwin/camera';
import { backoffDelay, type Backoff } from '@armtwin/protocol';
import { Segmenter } from './segmenter.ts';
import { Takes, type EndReason } from './takes.ts';
import type { RecordingCounters } from './recording-counters.ts';
import type { Segment } from './segment-files.ts';

export interface CameraRecorderOptions {
  armId: string;
  camId: string;
  /** The camera's `ws(s)://…/camera/<cam>.h264` URL. */
  url: string;
  /** `Authorization` header for the camera server ('' = none). */
  authorization: string;
  /** Its folder (`<dir>/<arm>/<cam>`). */
  dir: string;
  ffmpeg: string;
  segmentS: number;
  maxGapMs: number;
  /** ffmpeg's unread input beyond which the take ends (it cannot keep up), bytes. */
  maxBacklogBytes: number;
  backoff: Backoff;
  /** Epoch ms up to which this camera's frames are on disk. */
  recordedUntilMs: number;
  counters: RecordingCounters;
  onSegment(segment: Segment): void;
}

export class CameraRecorder {
  private ws: WebSocket | null = null;
  private take: Segmenter | null = null;
  private readonly endings = new Set<Promise<void>>();
  private readonly takes: Takes;
  private failures = 0;
  private timer: ReturnType<typeof setTimeout> | null = null;
  private stopped = false;

  constructor(private readonly o: CameraRecorderOptions) {
    this.takes = new Takes(o.recordedUntilMs, { maxGapMs: o.maxGapMs });
  }

  start(): void {
    this.connect();
  }

  /** Closes the feed and the take (its last segment is finished and renamed). */
  async stop(): Promise<void> {
    this.stopped = true;
    if (this.timer) clearTimeout(this.timer);
    this.ws?.terminate();
    this.endTake(this.takes.end('stop'));
    await Promise.all([...this.endings]);
  }

  private connect(): void {
    this.timer = null;
    const headers = this.o.authorization ? { authorization: this.o.authorization } : undefined;
    const ws = new WebSocket(this.o.url, { headers, perMessageDeflate: false });
    this.ws = ws;
    ws.binaryType = 'nodebuffer';
    ws.on('open', () => {
      this.o.counters.event('connects');
    });
    ws.on('message', (data: Buffer, binary) => {
      if (!binary) return;
      this.failures = 0;
      this.frame(data);
    });
    ws.on('error', (err) =>
      this.o.counters.problem('connect-failed', `${this.o.url}: ${err.message}`),
    );
    ws.on('close', () => {
      if (this.ws !== ws) return;
      this.ws = null;
      this.endTake(this.takes.end('disconnect'));
      if (this.stopped) return;
      const delay = backoffDelay(this.failures++, this.o.backoff);
      this.timer = setTimeout(() => this.connect(), delay);
    });
  }

  private frame(data: Buffer): void {
    const m = decodeH264Message(data);
    if (!m.ok) return this.o.counters.problem(`wire-${m.error}`, `bad h264-ws message: ${m.error}`);
    const { key, timestampMs, data: au } = m.message;
    const step = this.takes.frame(au, key, timestampMs);
    this.endTake(step.endTake);
    if (step.kind === 'drop') return this.o.counters.event(`frames-dropped-${step.why}`);
    if (step.bumped) this.o.counters.event('frame-times-bumped');
    if (step.startTake) this.startTake(au);
    const take = this.take;
    if (!take) return;
    if (take.backlogBytes > this.o.maxBacklogBytes) {
      this.o.counters.problem('ffmpeg-behind', 'the segmenter cannot keep up: the take ends');
      this.endTake(this.takes.end('gap'));
      return;
    }
    take.write(flvFrame(au, key, step.atMs));
    this.o.counters.frame(au.length);
  }

  private startTake(keyFrame: Uint8Array): void {
    const head = flvStart(keyFrame);
    const baseMs = this.takes.baseMs;
    if (!head || baseMs === null) return;
    this.o.counters.event('takes');
    this.take = new Segmenter({
      ffmpeg: this.o.ffmpeg,
      dir: this.o.dir,
      segmentS: this.o.segmentS,
      baseMs,
      onSegment: (s) => this.o.onSegment({ ...s, armId: this.o.armId, camId: this.o.camId }),
      onProblem: (kind, message) => this.o.counters.problem(kind, message),
    });
    this.take.write(head);
  }

  private endTake(why: EndReason | null): void {
    if (!why) return;
    this.o.counters.event(`takes-ended-${why}`);
    const take = this.take;
    this.take = null;
    if (!take) return;
    const ending: Promise<void> = take.end().finally(() => this.endings.delete(ending));
    this.endings.add(ending);
  }
}
