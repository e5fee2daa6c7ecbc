/**
 * One joint of the predictive twin: where the joint is at an instant of the arm's clock, from
 * its newest reports and from what it was last commanded. Times are the arm's (`$TIM` ms),
 * angles are servo degrees. Pure: plain numbers in and out, no clock, no DOM, no allocation.
 *
 * The prediction is the newest report moved on at a velocity:
 * - while a command is followed (target, duration T and the servo's top speed of PROTOCOL.md
 *   §4, as the controller moves: linear from where it is to the target in max(T, distance /
 *   top speed)), the command's velocity, only inside the command's time span;
 * - otherwise (no command seen, or the reports left the command's course: a stall, a stop,
 *   a collision, someone else's move) the velocity between the two newest reports.
 * It never passes the commanded target nor the joint's limits, and never runs further than
 * `maxLeadMs` (`maxCourseLeadMs` on a command's course) ahead of the newest report. A report that disagrees with the command's course
 * ends the command's say at once, so the drawn pose returns to the reports with that report.
 */

export interface JointPredictorOptions {
  /** A report's resolution, degrees (1 µs of a pulse report = 0.135°). */
  quantumDeg: number;
  /** A report further than quantum + this from the command's course leaves it, degrees. */
  divergeDeg: number;
  /** Furthest the reported velocity is extrapolated past the newest report, ms. */
  maxLeadMs: number;
  /**
   * Furthest a followed command's course is drawn past the newest report, ms (reports held up
   * by a busy page or network; the course still ends at its target).
   */
  maxCourseLeadMs: number;
  /** Reports further apart than this are a pause: no velocity is taken from them, ms. */
  maxGapMs: number;
  /** The same target again within this time is the same command (a page hears its own), ms. */
  sameCommandMs: number;
  /**
   * How long after the page saw a command the arm may still not have begun it (its way to the
   * arm), ms: a report in that time that shows the joint exactly where it was moves the
   * course's start on, instead of fixing it there.
   */
  startLatencyMs: number;
}

export const DEFAULT_JOINT_PREDICTOR_OPTIONS: JointPredictorOptions = {
  quantumDeg: 0.135,
  divergeDeg: 0.05,
  maxLeadMs: 200,
  maxCourseLeadMs: 1000,
  maxGapMs: 250,
  sameCommandMs: 300,
  startLatencyMs: 300,
};

export class JointPredictor {
  /** Newest report (stamp ms, angle °) and the one before. */
  s0 = NaN;
  a0 = NaN;
  s1 = NaN;
  a1 = NaN;
  /** The command followed: target (NaN = none), velocity °/ms over [start, end]. */
  target = NaN;
  /** Where the command found the joint (its course starts there at `start`). */
  from = NaN;
  vCmd = 0;
  start = NaN;
  end = NaN;
  /** When the page saw the command (arm ms): its course starts no earlier. */
  private issued = NaN;
  /** Whether the reports still agree with the command (its velocity is used). */
  following = false;
  /** A report has come since the command started (the first may correct its start). */
  private confirmed = false;
  /** The first report on the command's course: later ones are checked against the course. */
  private cs = NaN;
  private ca = NaN;
  /** After a stop at this time the joint is not extrapolated (until it moves again). */
  private heldFrom = Infinity;

  constructor(
    /** Joint limits, degrees, and top speed, ° per ms. */
    public minDeg: number,
    public maxDeg: number,
    public vmax: number,
    readonly opts: JointPredictorOptions = DEFAULT_JOINT_PREDICTOR_OPTIONS,
  ) {}

  /** A report: the joint was at `angle` at `stamp`. Older reports than the newest are ignored. */
  report(stamp: number, angle: number): void {
    if (!Number.isFinite(stamp) || !Number.isFinite(angle)) return;
    if (stamp < this.s0) return;
    if (stamp === this.s0) {
      this.a0 = angle;
      return;
    }
    const tol = this.opts.quantumDeg + this.opts.divergeDeg;
    let diverged = false;
    if (this.following && !Number.isNaN(this.a0)) {
      const expected = this.along(stamp);
      const moved = angle - this.a0;
      const onItsWay = moved * this.vCmd > 0 && Math.abs(moved) > tol;
      if (
        !this.confirmed &&
        moved === 0 &&
        stamp > this.start &&
        stamp <= this.issued + this.opts.startLatencyMs
      ) {
        // Not begun by this report: the command is still on its way to the arm (a loaded page,
        // broker or network), so its course starts after this report, not at it.
        this.end += stamp - this.start;
        this.start = stamp;
      } else if (!this.confirmed && (stamp > this.start || onItsWay)) {
        // The command's start is the page's estimate (when the page took the command in); the
        // first report after it, or the first that shows the joint on its way, sets the phase.
        this.confirmed = true;
        if (this.vCmd !== 0 && moved * this.vCmd >= 0 && Math.abs(angle - expected) > tol) {
          const shift = Math.max(this.s0, stamp - moved / this.vCmd) - this.start;
          this.start += shift;
          this.end += shift;
        }
        this.cs = stamp;
        this.ca = angle;
      } else if (
        Math.abs(angle - expected) > tol ||
        (this.confirmed && Math.abs(angle - this.course(stamp)) > tol)
      ) {
        this.following = false;
        diverged = true;
      }
    }
    if (stamp > this.heldFrom + this.opts.maxGapMs && Math.abs(angle - this.a0) > tol)
      this.heldFrom = Infinity;
    // Off the command's course, the velocity is taken from reports after this one only.
    this.s1 = diverged ? NaN : this.s0;
    this.a1 = this.a0;
    this.s0 = stamp;
    this.a0 = angle;
  }

  /**
   * A move to `targetDeg` in `durMs`, started on the arm at about `at` (arm ms). The same
   * target again soon after (the page's own command heard back) changes nothing.
   */
  command(targetDeg: number, durMs: number, at: number): void {
    if (!Number.isFinite(targetDeg) || !Number.isFinite(at)) return;
    const target = Math.min(this.maxDeg, Math.max(this.minDeg, targetDeg));
    if (target === this.target && Math.abs(at - this.start) < this.opts.sameCommandMs) return;
    const from = Number.isNaN(this.a0) ? target : this.predict(at);
    const dur = Math.max(Math.max(0, durMs), Math.abs(target - from) / this.vmax);
    this.target = target;
    this.from = from;
    this.vCmd = dur > 0 ? (target - from) / dur : 0;
    this.start = this.issued = at;
    this.end = at + dur;
    this.following = true;
    this.confirmed = false;
    this.heldFrom = Infinity;
  }

  /** A stop at about `at` (arm ms): the joint stays where it is then. */
  stop(at: number): void {
    if (!Number.isFinite(at)) return;
    if (!Number.isNaN(this.end)) this.end = Math.min(this.end, at);
    this.target = NaN;
    this.heldFrom = at;
  }

  /** Where the command's course puts the joint at `t`, from its first report on it. */
  private course(t: number): number {
    const from = Math.max(this.cs, this.start);
    const to = Math.min(t, this.end);
    const p = to > from ? this.ca + this.vCmd * (to - from) : this.ca;
    const target = this.target;
    return !Number.isNaN(target) && (target - this.ca) * (p - target) > 0 ? target : p;
  }

  /**
   * Where the last command (or stop) has the joint at `t`, however the reports went: its
   * course from where it found the joint; NaN when none was seen.
   */
  commandedAt(t: number): number {
    if (Number.isNaN(this.from)) return NaN;
    const dt = Math.min(t, this.end) - this.start;
    return dt > 0 ? this.from + this.vCmd * dt : this.from;
  }

  /** Velocity between the two newest reports, ° per ms (0 across a pause). */
  reportVelocity(): number {
    const dt = this.s0 - this.s1;
    if (!(dt > 0 && dt <= this.opts.maxGapMs)) return 0;
    return (this.a0 - this.a1) / dt;
  }

  /** The joint's angle at arm time `t` (NaN before the first report). */
  predict(t: number): number {
    const lead = this.following ? this.opts.maxCourseLeadMs : this.opts.maxLeadMs;
    return this.along(Math.min(t, this.s0 + lead));
  }

  /** The newest report moved on to `t`, however far. */
  private along(t: number): number {
    const a0 = this.a0;
    if (Number.isNaN(a0)) return NaN;
    const until = Math.min(t, this.heldFrom);
    if (!(until > this.s0)) return a0;
    let p: number;
    if (this.following) {
      const from = Math.max(this.s0, this.start);
      const to = Math.min(until, this.end);
      p = to > from ? a0 + this.vCmd * (to - from) : a0;
    } else {
      p = a0 + this.reportVelocity() * (until - this.s0);
    }
    const target = this.target;
    // Past the target on the far side from the newest report, or from where the command found
    // the joint when that report is on the target itself (reports and targets are whole pulses,
    // so an arriving joint often is exactly there).
    const side = a0 !== target ? target - a0 : target - this.from;
    if (!Number.isNaN(target) && side * (p - target) > 0) p = target;
    return Math.min(this.maxDeg, Math.max(this.minDeg, p));
  }

  /** Forgets everything (a new arm, a reconnect). */
  reset(): void {
    this.s0 = this.a0 = this.s1 = this.a1 = NaN;
    this.target = this.from = this.start = this.end = this.issued = this.cs = this.ca = NaN;
    this.vCmd = 0;
    this.following = this.confirmed = false;
    this.heldFrom = Infinity;
  }
}
