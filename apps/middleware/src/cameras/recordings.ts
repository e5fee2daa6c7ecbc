/**
 * Every camera's recording (docs/cameras-recording.md): the cameras come from their retained
 * announcements (PROTOCOL.md §7, `arm/+/camera/+`), each is recorded (its `h264-ws` stream, or
 * its MJPEG one when it has no other) by a ./camera-recorder.ts into `<dir>/<arm>/<cam>/`, retention (./segment-files.ts) runs after
 * each new segment and on a timer, and the HTTP API lists and serves the finished segments. At
 * start, `.part` files a crash left are deleted, and each camera's recording goes on after the
 * last frame already on disk.
 */
import fs from 'node:fs';
import path from 'node:path';
import { cameraStreams, parseCameraMessage, type CameraStream } from '@armtwin/camera/announcement';
import { CameraRecorder } from './camera-recorder.ts';
import { RecordingCounters } from './recording-counters.ts';
import { readCameraFolders } from './segment-folder.ts';
import {
  retentionPlan,
  segmentsBetween,
  type RetentionOptions,
  type Segment,
} from './segment-files.ts';
import type { Backoff } from '@armtwin/protocol';

export interface RecordingsOptions extends RetentionOptions {
  /** The recordings' folder. */
  dir: string;
  ffmpeg: string;
  /** Target segment length, s. */
  segmentS: number;
  /** A pause between two frames longer than this ends a take (a gap), ms. */
  maxGapMs: number;
  maxBacklogBytes: number;
  /** `Authorization` header sent to the camera servers ('' = none). */
  authorization: string;
  /** A certificate trusted besides the usual roots for `wss://` cameras (up's own; see ./camera-feeds.ts). */
  ca?: Buffer;
  backoff: Backoff;
  /** How often retention runs besides after each segment, ms. */
  retentionCheckMs: number;
  now: () => number;
  onFirst: (kind: string, message: string) => void;
}

export const DEFAULT_RECORDINGS_OPTIONS = {
  ffmpeg: 'ffmpeg',
  segmentS: 10,
  maxGapMs: 2000,
  maxBacklogBytes: 16 * 1024 * 1024,
  authorization: '',
  backoff: { minMs: 500, maxMs: 10_000 },
  retentionCheckMs: 60_000,
  now: Date.now,
  onFirst: () => {},
} satisfies Partial<RecordingsOptions>;

const key = (armId: string, camId: string) => `${armId}/${camId}`;

/** The stream recorded: the camera's H.264 one if it has one (no re-encode, smaller), else MJPEG. */
const recordedStream = (streams: CameraStream[]): CameraStream | undefined =>
  streams.find((s) => s.kind === 'h264-ws') ?? streams.find((s) => s.kind === 'mjpeg');

export class Recordings {
  readonly counters: RecordingCounters;
  private readonly o: RecordingsOptions;
  private readonly recorders = new Map<string, { url: string; recorder: CameraRecorder }>();
  private readonly index = new Map<string, Segment[]>();
  private timer: ReturnType<typeof setInterval> | null = null;

  constructor(
    options: Partial<RecordingsOptions> & Pick<RecordingsOptions, 'dir' | 'maxAgeMs' | 'maxBytes'>,
  ) {
    this.o = { ...DEFAULT_RECORDINGS_OPTIONS, ...options };
    this.counters = new RecordingCounters(this.o.onFirst);
    this.scan();
    this.applyRetention();
    this.timer = setInterval(() => this.applyRetention(), this.o.retentionCheckMs);
    this.timer.unref();
  }

  /** A message on `arm/+/camera/+`: starts, moves or stops that camera's recorder. */
  handle(topic: string, payload: Uint8Array | string): void {
    const m = parseCameraMessage(topic, payload);
    if (m.type === 'rejected') return this.counters.event(`announcements-rejected-${m.reason}`);
    const k = key(m.armId, m.camId);
    const stream = m.type === 'camera' ? recordedStream(cameraStreams(m.camera)) : undefined;
    const url = stream?.url;
    const current = this.recorders.get(k);
    if (current && current.url === url) return;
    if (current) {
      this.recorders.delete(k);
      void current.recorder.stop();
    }
    if (!stream || !url) return;
    const dir = path.join(this.o.dir, m.armId, m.camId);
    const recordedUntilMs = Math.max(0, ...(this.index.get(k) ?? []).map((s) => s.endMs));
    const recorder = new CameraRecorder({
      armId: m.armId,
      camId: m.camId,
      kind: stream.kind === 'h264-ws' ? 'h264' : 'mjpeg',
      url,
      authorization: this.o.authorization,
      ...(this.o.ca ? { ca: this.o.ca } : {}),
      dir,
      ffmpeg: this.o.ffmpeg,
      segmentS: this.o.segmentS,
      maxGapMs: this.o.maxGapMs,
      maxBacklogBytes: this.o.maxBacklogBytes,
      backoff: this.o.backoff,
      recordedUntilMs,
      counters: this.counters,
      now: this.o.now,
      onSegment: (s) => this.added(s),
    });
    this.recorders.set(k, { url, recorder });
    this.counters.event(stream.kind === 'h264-ws' ? 'cameras-recorded' : 'cameras-recorded-mjpeg');
    recorder.start();
  }

  /** The finished segments of a camera that hold any frame of [fromMs, toMs], by time. */
  segments(armId: string, camId: string, fromMs = 0, toMs = Number.MAX_SAFE_INTEGER): Segment[] {
    return segmentsBetween(this.index.get(key(armId, camId)) ?? [], fromMs, toMs);
  }

  /** The path of a finished segment by its name, or null. */
  file(armId: string, camId: string, name: string): string | null {
    const found = this.index.get(key(armId, camId))?.some((s) => s.name === name);
    return found ? path.join(this.o.dir, armId, camId, name) : null;
  }

  /** Deletes what retention says must go (oldest first); also run after each segment. */
  applyRetention(): void {
    const all = [...this.index.values()].flat();
    const plan = retentionPlan(all, this.o.now(), this.o);
    for (const { segment: s, why } of plan.deletions) {
      try {
        fs.rmSync(path.join(this.o.dir, s.armId, s.camId, s.name), { force: true });
      } catch (err) {
        this.counters.problem('delete-failed', `${s.name}: ${(err as Error).message}`);
        continue;
      }
      const list = this.index.get(key(s.armId, s.camId))!;
      list.splice(list.indexOf(s), 1);
      this.counters.event(`segments-deleted-${why}`);
    }
    this.gauges();
  }

  /** Stops every recorder; each finishes its last segment. */
  async stop(): Promise<void> {
    if (this.timer) clearInterval(this.timer);
    this.timer = null;
    const all = [...this.recorders.values()];
    this.recorders.clear();
    await Promise.all(all.map((r) => r.recorder.stop()));
  }

  private added(s: Segment): void {
    const k = key(s.armId, s.camId);
    const list = this.index.get(k) ?? [];
    list.push(s);
    this.index.set(k, list);
    this.counters.event('segments-written');
    this.applyRetention();
  }

  private gauges(): void {
    const all = [...this.index.values()].flat();
    this.counters.segments = all.length;
    this.counters.bytesStored = all.reduce((n, s) => n + s.bytes, 0);
  }

  /** Reads what is on disk; deletes the `.part` files a crash left behind. */
  private scan(): void {
    for (const c of readCameraFolders(this.o.dir)) {
      for (const part of c.parts) {
        fs.rmSync(path.join(c.dir, part), { force: true });
        this.counters.event('parts-discarded');
      }
      this.index.set(key(c.armId, c.camId), c.segments);
    }
    this.gauges();
  }
}
