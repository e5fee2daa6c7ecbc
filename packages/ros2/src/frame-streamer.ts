/**
 * Sends timed frames (./trajectory.ts) each at its time from the start of the run, on one timer
 * at a time. A new run replaces the one under way, as a new trajectory replaces the old one in
 * joint_trajectory_controller. Times are taken from the injected clock, so a late timer does not
 * push the rest of the run later.
 */
import type { TimedFrame } from '@armtwin/motion';
import type { Clock } from '@armtwin/protocol';

export class FrameStreamer {
  private frames: readonly TimedFrame[] = [];
  private next = 0;
  private start = 0;
  private timer: unknown;

  constructor(
    private readonly clock: Clock,
    private readonly send: (frame: string) => void,
  ) {}

  /** Whether a run is under way. */
  get running(): boolean {
    return this.next < this.frames.length;
  }

  play(frames: readonly TimedFrame[]): void {
    this.cancel();
    this.frames = frames;
    this.start = this.clock.now();
    this.pump();
  }

  cancel(): void {
    if (this.timer !== undefined) this.clock.clearTimeout(this.timer);
    this.timer = undefined;
    this.frames = [];
    this.next = 0;
  }

  private pump(): void {
    this.timer = undefined;
    const elapsed = this.clock.now() - this.start;
    while (this.next < this.frames.length && this.frames[this.next]!.at <= elapsed)
      this.send(this.frames[this.next++]!.frame);
    if (this.next < this.frames.length)
      this.timer = this.clock.setTimeout(() => this.pump(), this.frames[this.next]!.at - elapsed);
  }
}
