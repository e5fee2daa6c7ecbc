/**
 * One camera's stream drawn into a `<canvas>`, outside React: connects, draws each frame as it
 * is decoded, and when the stream ends or fails says since when, then reconnects with back-off.
 * Subclasses (./MjpegPlayer.ts, ./H264Player.ts) only open the stream; frames never touch React
 * state — the panel samples `stats` a few times a second.
 */
import { backoffDelay, type Backoff } from '@armtwin/protocol';
import type { CameraCredentials } from './streamUrl.ts';

export interface CameraPlayerOptions {
  /** Reconnect delays: `minMs`, doubled after each failure up to `maxMs`. */
  backoff: Backoff;
  /** Most frames waiting to be decoded; older ones are dropped and counted. */
  maxQueued: number;
}

export const DEFAULT_CAMERA_PLAYER_OPTIONS: CameraPlayerOptions = {
  backoff: { minMs: 500, maxMs: 10_000 },
  maxQueued: 3,
};

export interface CameraPlayerStats {
  /** Frames drawn. */
  frames: number;
  /** Frames dropped before decoding (a full queue) or undecodable. */
  dropped: number;
  /** Epoch ms of the last frame drawn, 0 = none yet. */
  lastFrameAt: number;
  /** Epoch ms since which the stream is gone, 0 = live or connecting. */
  offlineSince: number;
  /** Why it is offline. */
  reason: string;
  connects: number;
}

export abstract class CameraPlayer {
  readonly stats: CameraPlayerStats = {
    frames: 0,
    dropped: 0,
    lastFrameAt: 0,
    offlineSince: 0,
    reason: '',
    connects: 0,
  };
  protected readonly opts: CameraPlayerOptions;
  protected readonly ctx: CanvasRenderingContext2D | null;
  /** Failed connections since the last frame drawn. */
  private failures = 0;
  private retry: ReturnType<typeof setTimeout> | undefined;
  private disposed = false;
  /** Bumped per connection: callbacks of an older one are ignored. */
  protected generation = 0;

  constructor(
    readonly canvas: HTMLCanvasElement,
    /** The stream; a subclass checks its scheme again where it is opened. */
    protected readonly url: URL,
    protected readonly credentials: CameraCredentials,
    opts: Partial<CameraPlayerOptions> = {},
  ) {
    this.opts = { ...DEFAULT_CAMERA_PLAYER_OPTIONS, ...opts };
    this.ctx = canvas.getContext('2d');
  }

  start(): void {
    this.connect();
  }

  dispose(): void {
    this.disposed = true;
    clearTimeout(this.retry);
    this.generation++;
    this.close();
  }

  /** Opens the stream for connection `gen`; calls `drawFrame` and `failed` with it. */
  protected abstract open(gen: number): void;
  /** Closes whatever `open` opened. */
  protected abstract close(): void;

  private connect(): void {
    if (this.disposed) return;
    this.stats.connects++;
    this.open(++this.generation);
  }

  /** Draws one decoded picture (resizing the canvas to it). */
  protected drawFrame(gen: number, image: CanvasImageSource, width: number, height: number): void {
    if (gen !== this.generation || !this.ctx) return;
    if (this.canvas.width !== width || this.canvas.height !== height) {
      this.canvas.width = width;
      this.canvas.height = height;
    }
    this.ctx.drawImage(image, 0, 0, width, height);
    this.stats.frames++;
    this.stats.lastFrameAt = Date.now();
    this.stats.offlineSince = 0;
    this.stats.reason = '';
    this.failures = 0;
  }

  /** The stream ended or failed: offline since now (or since before), retry after the back-off. */
  protected failed(gen: number, reason: string): void {
    if (gen !== this.generation || this.disposed) return;
    this.generation++;
    this.close();
    if (!this.stats.offlineSince) this.stats.offlineSince = Date.now();
    this.stats.reason = reason;
    clearTimeout(this.retry);
    this.retry = setTimeout(() => this.connect(), backoffDelay(this.failures++, this.opts.backoff));
  }
}
