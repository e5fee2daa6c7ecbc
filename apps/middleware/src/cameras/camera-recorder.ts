/**
 * Records one camera: a viewer of its feed (./camera-feeds.ts: `h264-ws`, or MJPEG for a camera
 * that offers only that), like a HUD, that hands the frames ./takes.ts keeps to a writer per
 * take: for H.264 a ./segmenter.ts ffmpeg (`-c copy` into MP4), for MJPEG a
 * ./jpeg-segmenter.ts (the JPEGs as served). The connection is opened again after a back-off
 * whenever it drops (the camera server restarted); each drop is one gap. The frames are the
 * ones the server sends every viewer: nothing is decoded or encoded.
 */
import { flvFrame, flvStart } from '@armtwin/camera';
import { backoffDelay, type Backoff } from '@armtwin/protocol';
import { openH264Feed, openMjpegFeed, type Feed, type FeedHandlers } from './camera-feeds.ts';
import { JpegSegmenter } from './jpeg-segmenter.ts';
import { Segmenter } from './segmenter.ts';
import { anyFrame, Takes, type EndReason } from './takes.ts';
import type { RecordingCounters } from './recording-counters.ts';
import type { Segment, SegmentKind } from './segment-files.ts';

export interface CameraRecorderOptions {
  armId: string;
  camId: string;
  /** What the feed is: `h264` (`ws(s)://…/camera/<cam>.h264`) or `mjpeg` (`http(s)://…`). */
  kind: SegmentKind;
  url: string;
  /** `Authorization` header for the camera server ('' = none). */
  authorization: string;
  /** A certificate trusted besides the usual roots (`h264` feeds only: ./camera-feeds.ts). */
  ca?: Buffer;
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
  now: () => number;
  onSegment(segment: Segment): void;
}

/** One take's writer: the frame at `atMs` from the take's first (`baseMs`). */
interface TakeWriter {
  readonly backlogBytes: number;
  write(frame: Uint8Array, key: boolean, atMs: number): void;
  end(): Promise<void>;
}

export class CameraRecorder {
  private feed: Feed | null = null;
  private take: TakeWriter | null = null;
  private readonly endings = new Set<Promise<void>>();
  private readonly takes: Takes;
  private failures = 0;
  private timer: ReturnType<typeof setTimeout> | null = null;
  private stopped = false;

  constructor(private readonly o: CameraRecorderOptions) {
    this.takes = new Takes(o.recordedUntilMs, {
      maxGapMs: o.maxGapMs,
      ...(o.kind === 'mjpeg' ? { parametersOf: anyFrame } : {}),
    });
  }

  start(): void {
    this.connect();
  }

  /** Closes the feed and the take (its last segment is finished and renamed). */
  async stop(): Promise<void> {
    this.stopped = true;
    if (this.timer) clearTimeout(this.timer);
    this.feed?.close();
    this.endTake(this.takes.end('stop'));
    await Promise.all([...this.endings]);
  }

  private connect(): void {
    this.timer = null;
    let feed: Feed | null = null;
    const h: FeedHandlers = {
      open: () => this.o.counters.event('connects'),
      frame: (data, key, atMs) => {
        this.failures = 0;
        this.frame(data, key, atMs);
      },
      problem: (kind, message) => this.o.counters.problem(kind, message),
      event: (kind) => this.o.counters.event(kind),
      closed: () => {
        if (this.feed !== feed) return;
        this.feed = null;
        this.endTake(this.takes.end('disconnect'));
        if (this.stopped) return;
        const delay = backoffDelay(this.failures++, this.o.backoff);
        this.timer = setTimeout(() => this.connect(), delay);
      },
    };
    feed =
      this.o.kind === 'mjpeg'
        ? openMjpegFeed(this.o.url, this.o.authorization, h, this.o.now)
        : openH264Feed(this.o.url, this.o.authorization, h, this.o.ca);
    this.feed = feed;
  }

  private frame(au: Uint8Array, key: boolean, timestampMs: number): void {
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
    take.write(au, key, step.atMs);
    this.o.counters.frame(au.length);
  }

  private startTake(keyFrame: Uint8Array): void {
    const baseMs = this.takes.baseMs;
    if (baseMs === null) return;
    const common = {
      dir: this.o.dir,
      segmentS: this.o.segmentS,
      baseMs,
      onSegment: (s: Pick<Segment, 'name' | 'startMs' | 'endMs' | 'bytes'>) =>
        this.o.onSegment({ ...s, armId: this.o.armId, camId: this.o.camId }),
      onProblem: (kind: string, message: string) => this.o.counters.problem(kind, message),
    };
    if (this.o.kind === 'mjpeg') {
      const jpegs = new JpegSegmenter(common);
      this.take = {
        backlogBytes: 0,
        write: (jpeg, _key, atMs) => jpegs.write(jpeg, baseMs + atMs),
        end: () => jpegs.end(),
      };
    } else {
      const head = flvStart(keyFrame);
      if (!head) return;
      const flv = new Segmenter({ ...common, ffmpeg: this.o.ffmpeg });
      flv.write(head);
      this.take = {
        get backlogBytes() {
          return flv.backlogBytes;
        },
        write: (au, key, atMs) => flv.write(flvFrame(au, key, atMs)),
        end: () => flv.end(),
      };
    }
    this.o.counters.event('takes');
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
