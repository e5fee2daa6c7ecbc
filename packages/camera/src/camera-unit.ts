/**
 * One served camera: its ffmpeg (kept running by an `FfmpegRunner`), the parsers that cut
 * ffmpeg's pipes into frames, the `CameraFeed` its viewers watch, and its counters by kind.
 * An MJPEG URL that is passed through (announced as it is) has no ffmpeg and no feed here.
 */
import type { Logger } from 'pino';
import {
  cameraTopic,
  encodeAnnouncement,
  type CameraAnnouncement,
  type CameraKind,
  type CameraPose,
  type CameraStream,
} from './announcement.ts';
import { CameraFeed, type CameraFeedOptions, type KindStats } from './camera-feed.ts';
import {
  describeSource,
  ffmpegArgs,
  parseSource,
  type CameraSource,
  type EncoderOptions,
} from './ffmpeg-args.ts';
import { FfmpegRunner, type BackoffOptions, type FfmpegRunnerStats } from './ffmpeg-runner.ts';
import { createFlvH264Reader, type FlvH264Reader } from './flv-h264.ts';
import { createSmjpegParser, type SmjpegParser } from './smjpeg-parser.ts';
import { captureTime } from './capture-time.ts';

/** What to serve: one camera of one arm. */
export interface CameraSpec {
  armId: string;
  camId: string;
  /** Shown in the HUD, as text. */
  label: string;
  /** `testsrc`, a V4L2 device, an `rtsp://` URL or an `http(s)://` MJPEG URL. */
  source: string;
  pose?: CameraPose;
  fovDeg?: number;
  /** Kinds served, the first one announced as the main stream (default mjpeg, then h264-ws). */
  kinds?: CameraKind[];
  /**
   * An `http(s)://` MJPEG source is announced as it is, not re-served (default). False: ffmpeg
   * reads it and this server serves it in every kind, behind its own log-ins.
   */
  passThrough?: boolean;
}

export const DEFAULT_KINDS: readonly CameraKind[] = ['mjpeg', 'h264-ws'];

/** Everything a unit needs from its server. */
export interface CameraUnitContext {
  ffmpeg: string;
  encoder: Partial<EncoderOptions>;
  feed: Partial<CameraFeedOptions>;
  backoff: BackoffOptions;
  stallMs: number;
  now: () => number;
  onFirst: (kind: string, message: string) => void;
  log?: Logger;
}

export interface CameraStats {
  armId: string;
  camId: string;
  label: string;
  source: string;
  kinds: CameraKind[];
  passThrough: boolean;
  ffmpeg: FfmpegRunnerStats | null;
  streams: Partial<Record<CameraKind, KindStats>>;
  /** Problems by kind: parser errors, ffmpeg exits, stalls, refused viewers. */
  errors: Record<string, number>;
}

const MJPEG_FD = 1;
const H264_FD = 3;

export class CameraUnit {
  readonly source: CameraSource;
  readonly kinds: CameraKind[];
  readonly passThrough: boolean;
  readonly feed: CameraFeed;
  readonly runner: FfmpegRunner | null;
  readonly topic: string;
  private readonly errors: Record<string, number> = {};
  private readonly jpeg: SmjpegParser;
  private readonly h264: FlvH264Reader;

  constructor(
    readonly spec: CameraSpec,
    private readonly ctx: CameraUnitContext,
  ) {
    this.topic = cameraTopic(spec.armId, spec.camId);
    this.source = parseSource(spec.source);
    this.passThrough = this.source.type === 'mjpeg-url' && spec.passThrough !== false;
    this.kinds = this.passThrough ? [] : [...new Set(spec.kinds ?? DEFAULT_KINDS)];
    if (!this.passThrough && this.kinds.length === 0)
      throw new RangeError(`camera ${spec.camId}: no kind to serve`);
    if (this.passThrough && /^[a-z]+:\/\/[^/]*@/i.test(spec.source))
      throw new RangeError(
        `camera ${spec.camId}: an MJPEG URL with a user name or password cannot be announced as it is (every reader of the topic would see it): re-serve it (passThrough: false)`,
      );
    encodeAnnouncement(this.announcement('http://127.0.0.1')); // label, pose, fov: checked now
    this.feed = new CameraFeed(ctx.feed);
    const now = ctx.now;
    this.jpeg = createSmjpegParser({
      onFrame: (f) => {
        this.runner?.frame();
        this.feed.jpeg(f.jpeg, this.frameTime('jpeg', f.timestampMs));
      },
      onError: (e) => this.count(`jpeg:${e.kind}`, e.message),
    });
    this.h264 = createFlvH264Reader({
      onAccessUnit: (au) => {
        this.runner?.frame();
        this.feed.accessUnit(au.data, au.key, this.frameTime('h264', au.timestampMs));
      },
      onError: (e) => this.count(`h264:${e.kind}`, e.message),
    });
    const serves = (k: CameraKind) => this.kinds.includes(k);
    const outputs: Record<number, (chunk: Buffer) => void> = {};
    if (serves('mjpeg')) outputs[MJPEG_FD] = (c) => this.jpeg.feed(c);
    if (serves('h264-ws')) outputs[H264_FD] = (c) => this.h264.feed(c);
    this.runner = this.passThrough
      ? null
      : new FfmpegRunner({
          command: ctx.ffmpeg,
          args: ffmpegArgs(this.source, ctx.encoder, {
            ...(serves('mjpeg') ? { mjpeg: MJPEG_FD } : {}),
            ...(serves('h264-ws') ? { h264: H264_FD } : {}),
          }),
          outputs,
          backoff: ctx.backoff,
          stallMs: ctx.stallMs,
          now,
          onStart: () => {
            this.jpeg.reset();
            this.h264.reset();
            this.feed.encoderRestarted();
          },
          onEvent: (kind, message) => this.count(`ffmpeg:${kind}`, message),
          onExit: (exit, restartInMs) => {
            if (restartInMs === null) return;
            ctx.log?.warn(
              { camera: spec.camId, reason: exit.reason, ranMs: exit.ranMs, restartInMs },
              'ffmpeg stopped; restarting',
            );
          },
        });
  }

  serves(kind: CameraKind): boolean {
    return this.kinds.includes(kind);
  }

  /**
   * A frame's time: its capture time from ffmpeg's stamp (./capture-time.ts), or, when that is
   * not the wall clock, the time the frame came out of ffmpeg, counted (`<kind>:frame-times-arrival`).
   */
  private frameTime(kind: 'jpeg' | 'h264', stamp: number): number {
    const now = this.ctx.now();
    const captured = captureTime(stamp, now);
    if (captured !== null) return captured;
    this.count(
      `${kind}:frame-times-arrival`,
      `ffmpeg's frame times are not the wall clock (${kind} stamp ${stamp}): frames are stamped when they come out of ffmpeg`,
    );
    return now;
  }

  /** Counts a problem; the first of each kind is also told to `onFirst`. */
  count(kind: string, message: string): void {
    const n = (this.errors[kind] = (this.errors[kind] ?? 0) + 1);
    if (n === 1)
      this.ctx.onFirst(`${this.spec.camId}/${kind}`, `camera ${this.spec.camId}: ${message}`);
  }

  /** The §7 announcement, with this server's URLs under `baseUrl` (`http(s)://host:port`). */
  announcement(baseUrl: string): CameraAnnouncement {
    const base = baseUrl.replace(/\/+$/, '');
    const url = (kind: CameraKind): string => {
      switch (kind) {
        case 'mjpeg':
          return `${base}/camera/${this.spec.camId}.mjpeg`;
        case 'h264-ws':
          return `${base.replace(/^http/, 'ws')}/camera/${this.spec.camId}.h264`;
        default:
          return assertNever(kind);
      }
    };
    const streams: CameraStream[] = this.passThrough
      ? [{ url: this.spec.source, kind: 'mjpeg' }]
      : this.kinds.map((kind) => ({ url: url(kind), kind }));
    const [main, ...alternates] = streams as [CameraStream, ...CameraStream[]];
    return {
      ...main,
      label: this.spec.label,
      ...(this.spec.pose ? { pose: this.spec.pose } : {}),
      ...(this.spec.fovDeg !== undefined ? { fovDeg: this.spec.fovDeg } : {}),
      alternates,
    };
  }

  stats(): CameraStats {
    const all = this.feed.stats();
    const streams: Partial<Record<CameraKind, KindStats>> = {};
    for (const k of this.kinds) streams[k] = all[k];
    return {
      armId: this.spec.armId,
      camId: this.spec.camId,
      label: this.spec.label,
      source: describeSource(this.source),
      kinds: this.kinds,
      passThrough: this.passThrough,
      ffmpeg: this.runner?.stats() ?? null,
      streams,
      errors: { ...this.errors },
    };
  }
}

function assertNever(x: never): never {
  throw new Error(`unhandled camera kind ${String(x)}`);
}
