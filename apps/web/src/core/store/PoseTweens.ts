/**
 * The `interpolate` way of drawing the arm (./ArmStore.ts's `twinMode`): each joint tweens
 * toward its newest report over the expected report interval, or, when reports come faster than
 * `drawNewestAboveHz`, jumps to it (a tween toward the newest report only lags then).
 */
import { IntervalEstimator, JointTween } from './interpolation.ts';

export class PoseTweens {
  private readonly tweens: JointTween[];
  private readonly interval = new IntervalEstimator();
  /** Whether the stream is fast enough to draw each report as it is. */
  private drawNewest = false;

  constructor(servoCount: number) {
    this.tweens = Array.from({ length: servoCount }, () => new JointTween());
  }

  /** A state report arrived at `now`, with reports coming at `ratePerS` (`aboveHz`: the switch). */
  arrive(now: number, ratePerS: number, aboveHz: number): void {
    this.interval.arrive(now);
    this.drawNewest = ratePerS >= aboveHz;
  }

  /** Joint `id` was reported at `deg`: tween there from where it is drawn at `now`. */
  retarget(id: number, deg: number, now: number, alpha: number): void {
    this.tweens[id]!.retarget(deg, now, this.drawNewest ? 0 : this.interval.intervalMs, alpha);
  }

  /** Joint `id`'s angle to draw at `now`, degrees. */
  valueAt(id: number, now: number, alpha: number): number {
    return this.tweens[id]!.valueAt(now, alpha);
  }

  /** The expected time between state reports, ms. */
  get intervalMs(): number {
    return this.interval.intervalMs;
  }

  reset(): void {
    for (const t of this.tweens) t.reset();
    this.interval.reset();
    this.drawNewest = false;
  }
}
