/**
 * Which frames of a camera's H.264 (or MJPEG) feed go into which take (one continuous run of frames, one
 * ffmpeg, a run of segments), pure. A take starts at a key frame carrying its parameter sets and
 * ends when the feed drops, when the frames stop for longer than `maxGapMs` (the camera server's
 * encoder restarted, or its viewer queue skipped far ahead) or when the parameter sets change:
 * the next take starts at the next key frame, and the time in between is a gap, never a frozen
 * frame or a corrupt file. A frame at or before the last one recorded (`recordedUntilMs`, from
 * the finished segments on disk at start) is dropped: a viewer's first frames are the server's
 * replay of its current group of pictures, which a middleware restarted within the second has
 * recorded already. Within a take, a frame stamped at or before the one before it (the server
 * stamps a frame when it has it, and two can come in one read) is written 1 ms after it.
 */
import { parameterSets, sameBytes } from '@armtwin/camera';

export interface TakesOptions {
  /** A longer pause between two frames ends the take, ms. */
  maxGapMs: number;
  /**
   * What a frame that can start a take carries that the take's frames must share, or null for a
   * frame that cannot start one: H.264's SPS of a key frame (the default); for MJPEG, where every
   * frame stands alone, `anyFrame`.
   */
  parametersOf(au: Uint8Array, key: boolean): Uint8Array | null;
}

const h264Parameters = (au: Uint8Array, key: boolean) =>
  key ? (parameterSets(au)?.sps ?? null) : null;
const NO_PARAMETERS = new Uint8Array(0);
/** Every frame starts a take, and none changes its parameters (an MJPEG camera's JPEGs). */
export const anyFrame = (): Uint8Array => NO_PARAMETERS;

export const DEFAULT_TAKES_OPTIONS: TakesOptions = { maxGapMs: 2000, parametersOf: h264Parameters };

/** What to do with one frame. */
export type TakeStep =
  | {
      kind: 'write';
      startTake: boolean;
      endTake: EndReason | null;
      /** From the take's first frame, ms. */
      atMs: number;
      /** The frame's time was moved to 1 ms after the one before. */
      bumped: boolean;
    }
  | { kind: 'drop'; why: DropReason; endTake: EndReason | null };

export const TAKE_END_REASONS = ['gap', 'parameters', 'disconnect', 'stop'] as const;
export type EndReason = (typeof TAKE_END_REASONS)[number];
export const DROP_REASONS = ['recorded-already', 'before-key-frame'] as const;
export type DropReason = (typeof DROP_REASONS)[number];

export class Takes {
  private take: { baseMs: number; lastMs: number; sps: Uint8Array } | null = null;
  private readonly o: TakesOptions;

  constructor(
    /** Epoch ms up to which frames are on disk already. */
    public recordedUntilMs: number,
    options: Partial<TakesOptions> = {},
  ) {
    this.o = { ...DEFAULT_TAKES_OPTIONS, ...options };
  }

  /** The open take's first frame time (epoch ms: its time 0), or null. */
  get baseMs(): number | null {
    return this.take?.baseMs ?? null;
  }

  /** Decides one frame (`au` in Annex B, a key frame with its SPS and PPS). */
  frame(au: Uint8Array, key: boolean, atMs: number): TakeStep {
    let endTake: EndReason | null = null;
    let bumped = false;
    if (this.take && atMs <= this.take.lastMs) {
      atMs = this.take.lastMs + 1;
      bumped = true;
    }
    if (atMs <= this.recordedUntilMs) return { kind: 'drop', why: 'recorded-already', endTake };
    const sps = this.o.parametersOf(au, key);
    if (this.take) {
      if (atMs - this.take.lastMs > this.o.maxGapMs) endTake = 'gap';
      else if (sps && !sameBytes(sps, this.take.sps)) endTake = 'parameters';
      if (endTake) this.take = null;
    }
    let startTake = false;
    if (!this.take) {
      if (!sps) return { kind: 'drop', why: 'before-key-frame', endTake };
      this.take = { baseMs: Math.round(atMs), lastMs: atMs, sps };
      startTake = true;
    }
    const at = atMs - this.take.baseMs;
    this.take.lastMs = atMs;
    this.recordedUntilMs = atMs;
    return { kind: 'write', startTake, endTake, atMs: Math.round(at), bumped };
  }

  /** The feed ended (or the recorder stops): the take, if any, ends. */
  end(why: EndReason): EndReason | null {
    if (!this.take) return null;
    this.take = null;
    return why;
  }
}
