/**
 * One stream's viewers, pure: each published frame goes to every viewer through its own
 * bounded `FrameQueue`, one write in flight per viewer. A viewer whose writes do not complete
 * (a slow network, a stalled tab) keeps at most `capacity` frames queued; the rest are dropped
 * and counted for it. Sockets are behind `FrameSink`, so a unit test needs none.
 */
import { FrameQueue, type DropPolicy } from './frame-queue.ts';

export interface FrameSink {
  /** Writes one message; calls `done` once it has left, or with the error that stopped it. */
  write(data: Uint8Array, done: (err?: Error | null) => void): void;
}

export interface FanoutOptions {
  policy: DropPolicy;
  /** Live frames queued per viewer at most. */
  capacity: number;
  /** Viewers at most; more are refused. */
  maxViewers: number;
}

export interface ViewerStats {
  id: number;
  remote: string;
  since: number;
  sent: number;
  dropped: number;
  queued: number;
}

export interface FanoutStats {
  framesIn: number;
  framesSent: number;
  /** Frames dropped, over all viewers, gone ones included. */
  dropped: number;
  /** Writes that failed (the viewer is removed). */
  writeErrors: number;
  viewers: ViewerStats[];
}

export interface Viewer {
  readonly id: number;
  readonly stats: ViewerStats;
}

interface Slot extends Viewer {
  sink: FrameSink;
  queue: FrameQueue<Uint8Array>;
  busy: boolean;
  gone: boolean;
  stats: ViewerStats;
}

export class Fanout {
  private readonly slots = new Map<number, Slot>();
  private nextId = 1;
  private framesIn = 0;
  private framesSent = 0;
  private droppedGone = 0;
  private writeErrors = 0;

  constructor(private readonly o: FanoutOptions) {}

  get viewerCount(): number {
    return this.slots.size;
  }

  /**
   * Adds a viewer; `initial` frames (the latest picture, or the current group of pictures) are
   * queued first as replay. Null when `maxViewers` are already watching.
   */
  add(
    sink: FrameSink,
    remote: string,
    now: number,
    initial: readonly { data: Uint8Array; key: boolean }[] = [],
  ): Viewer | null {
    if (this.slots.size >= this.o.maxViewers) return null;
    const id = this.nextId++;
    const slot: Slot = {
      id,
      sink,
      queue: new FrameQueue<Uint8Array>({ capacity: this.o.capacity, policy: this.o.policy }),
      busy: false,
      gone: false,
      stats: { id, remote, since: now, sent: 0, dropped: 0, queued: 0 },
    };
    this.slots.set(id, slot);
    for (const f of initial) slot.queue.push(f.data, f.key, true);
    this.pump(slot);
    return slot;
  }

  remove(viewer: Viewer): void {
    const slot = this.slots.get(viewer.id);
    if (!slot) return;
    slot.gone = true;
    this.droppedGone += slot.queue.dropped;
    this.slots.delete(viewer.id);
  }

  publish(data: Uint8Array, key: boolean): void {
    this.framesIn++;
    for (const slot of this.slots.values()) {
      slot.queue.push(data, key);
      this.pump(slot);
    }
  }

  /** The source started over (a new encoder): queued frames are stale; H.264 waits for a key. */
  restart(): void {
    for (const slot of this.slots.values()) slot.queue.restart();
  }

  stats(): FanoutStats {
    const viewers = [...this.slots.values()].map((s) => ({
      ...s.stats,
      dropped: s.queue.dropped,
      queued: s.queue.size,
    }));
    return {
      framesIn: this.framesIn,
      framesSent: this.framesSent,
      dropped: this.droppedGone + viewers.reduce((sum, v) => sum + v.dropped, 0),
      writeErrors: this.writeErrors,
      viewers,
    };
  }

  private pump(slot: Slot): void {
    if (slot.busy || slot.gone) return;
    const data = slot.queue.shift();
    if (!data) return;
    slot.busy = true;
    let called = false;
    slot.sink.write(data, (err) => {
      if (called) return;
      called = true;
      slot.busy = false;
      if (err) {
        this.writeErrors++;
        this.remove(slot);
        return;
      }
      slot.stats.sent++;
      this.framesSent++;
      this.pump(slot);
    });
  }
}
