/**
 * One viewer's bounded queue of frames not yet written to it, pure. When the viewer falls
 * behind, frames are dropped and counted, so it gets the newest picture instead of an ever
 * older one, and the server's memory stays bounded:
 *
 * - `latest` (MJPEG, every frame stands alone): full → the oldest queued frame is dropped.
 * - `until-key` (H.264, a frame needs the ones before it): full → everything queued is dropped
 *   and so is every frame up to the next key frame, which the decoder can start from. A key
 *   frame also supersedes whatever is still queued before it. A new queue waits for a key frame.
 *   Frames pushed as `replay` (the current group of pictures, for a viewer that just came) do
 *   not count against the capacity: the server bounds them.
 */
export const DROP_POLICIES = ['latest', 'until-key'] as const;
export type DropPolicy = (typeof DROP_POLICIES)[number];

export interface FrameQueueOptions {
  /** Live frames held at most. */
  capacity: number;
  policy: DropPolicy;
}

interface Entry<T> {
  frame: T;
  replay: boolean;
}

export class FrameQueue<T> {
  /** Frames dropped from this queue since it was made. */
  dropped = 0;
  private readonly items: Entry<T>[] = [];
  private live = 0;
  private waitingForKey: boolean;

  constructor(private readonly o: FrameQueueOptions) {
    if (!(o.capacity >= 1)) throw new RangeError('a frame queue holds at least one frame');
    this.waitingForKey = o.policy === 'until-key';
  }

  get size(): number {
    return this.items.length;
  }

  /** Whether H.264 frames are being skipped until the next key frame. */
  get skipping(): boolean {
    return this.waitingForKey;
  }

  push(frame: T, key: boolean, replay = false): void {
    switch (this.o.policy) {
      case 'latest':
        if (!replay && this.live >= this.o.capacity) this.dropOldestLive();
        break;
      case 'until-key':
        if (key) {
          this.clear();
          this.waitingForKey = false;
        } else if (this.waitingForKey) {
          this.dropped++;
          return;
        } else if (!replay && this.live >= this.o.capacity) {
          this.clear();
          this.dropped++;
          this.waitingForKey = true;
          return;
        }
        break;
      default:
        return assertNever(this.o.policy);
    }
    this.items.push({ frame, replay });
    if (!replay) this.live++;
  }

  shift(): T | undefined {
    const e = this.items.shift();
    if (e && !e.replay) this.live--;
    return e?.frame;
  }

  /** Drops everything queued (counted); an H.264 queue then waits for a key frame. */
  restart(): void {
    this.clear();
    this.waitingForKey = this.o.policy === 'until-key';
  }

  private clear(): void {
    this.dropped += this.items.length;
    this.items.length = 0;
    this.live = 0;
  }

  private dropOldestLive(): void {
    const i = this.items.findIndex((e) => !e.replay);
    if (i < 0) return;
    this.items.splice(i, 1);
    this.live--;
    this.dropped++;
  }
}

function assertNever(x: never): never {
  throw new Error(`unhandled drop policy ${String(x)}`);
}
