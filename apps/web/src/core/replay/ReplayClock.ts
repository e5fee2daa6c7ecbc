/**
 * The replay's clock: a position in record time (epoch ms) inside [start, stop], moved by
 * wall time × speed while playing, stopping at the end. Pure: the wall clock is passed to
 * `tick(now)` by the frame loop; `play()` starts counting from the next tick.
 */

export const REPLAY_SPEEDS = [0.25, 0.5, 1, 2, 4, 8] as const;
export type ReplaySpeed = (typeof REPLAY_SPEEDS)[number];

export class ReplayClock {
  start = 0;
  stop = 0;
  /** Record time shown now, epoch ms. */
  position = 0;
  speed: ReplaySpeed = 1;
  playing = false;
  /** Wall time of the previous tick while playing (NaN: the next tick only sets it). */
  private lastNow = NaN;

  /** A new record: position at its start, paused. */
  load(start: number, stop: number): void {
    this.start = start;
    this.stop = Math.max(start, stop);
    this.position = start;
    this.pause();
  }

  /** Plays from here (from the start again when at the end). */
  play(): void {
    if (this.position >= this.stop) this.position = this.start;
    this.playing = this.stop > this.start;
    this.lastNow = NaN;
  }

  pause(): void {
    this.playing = false;
    this.lastNow = NaN;
  }

  seek(t: number): void {
    this.position = Math.min(this.stop, Math.max(this.start, Number.isFinite(t) ? t : this.start));
  }

  setSpeed(speed: ReplaySpeed): void {
    this.speed = speed;
  }

  /** Advances by (now − previous tick) × speed while playing; pauses at the end. */
  tick(now: number): number {
    if (!this.playing) return this.position;
    if (!Number.isNaN(this.lastNow)) {
      const dt = Math.max(0, now - this.lastNow);
      this.position = Math.min(this.stop, this.position + dt * this.speed);
      if (this.position >= this.stop) this.pause();
    }
    if (this.playing) this.lastNow = now;
    return this.position;
  }

  /** 0…1 through the record. */
  get fraction(): number {
    return this.stop > this.start ? (this.position - this.start) / (this.stop - this.start) : 0;
  }
}
