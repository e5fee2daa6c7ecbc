/**
 * The predictive twin: every joint's pose at the display instant, not at the newest report.
 * Reports come in with their `$TIM` stamp and page arrival time; the clock offset between the
 * two (./ClockOffset.ts) turns the page's `now` into the arm's time; each joint
 * (./JointPredictor.ts) moves its newest report on by what was commanded or by its reported
 * velocity. `sample` also says whether what it drew is a prediction no report has confirmed
 * yet (the contract: never show a pose the arm is not in without saying so), and by how much.
 * Pure: plain numbers in, `now` passed in, no DOM, so it runs in the page or in a worker.
 */
import { ClockOffset, type ClockOffsetOptions } from './ClockOffset.ts';
import {
  DEFAULT_JOINT_PREDICTOR_OPTIONS,
  JointPredictor,
  type JointPredictorOptions,
} from './JointPredictor.ts';

/** How the twin draws the joints: predicted, the seed's interpolation, or the newest report. */
export const TWIN_MODES = ['predict', 'interpolate', 'newest'] as const;
export type TwinMode = (typeof TWIN_MODES)[number];
export const isTwinMode = (v: unknown): v is TwinMode => TWIN_MODES.includes(v as TwinMode);

/** One joint's limits (servo degrees) and top speed (° per s). */
export interface JointSpec {
  minDeg: number;
  maxDeg: number;
  maxSpeedDegPerS: number;
}

export interface TwinPredictorOptions {
  joint: JointPredictorOptions;
  clock: Partial<ClockOffsetOptions>;
  /**
   * How far past `now` the pose is predicted at first, ms: the time from sampling to the frame
   * on the screen. `shown` then learns it from the frames actually drawn.
   */
  displayLeadMs: number;
  /** Weight of the newest frame in the learnt display lead, 0 … 1 (0 = never learn). */
  displayLeadSmoothing: number;
  /** Largest display lead learnt, ms (a frame slower than this is a hiccup, not a habit). */
  maxDisplayLeadMs: number;
  /** A joint drawn more than this from its newest report is a prediction, degrees. */
  unconfirmedDeg: number;
}

export const DEFAULT_TWIN_PREDICTOR_OPTIONS: TwinPredictorOptions = {
  joint: DEFAULT_JOINT_PREDICTOR_OPTIONS,
  clock: {},
  displayLeadMs: 0,
  displayLeadSmoothing: 0.1,
  maxDisplayLeadMs: 100,
  unconfirmedDeg: 0.05,
};

export class TwinPredictor {
  readonly opts: TwinPredictorOptions;
  readonly clock: ClockOffset;
  private joints: JointPredictor[] = [];
  /** Set by `sample`: some joint is drawn where no report has put it yet. */
  predicting = false;
  /** Set by `sample`: how far ahead of the newest report the predicting joints are, ms. */
  leadMs = 0;
  /** The time from `sample` to its frame being drawn, ms, as learnt by `shown`. */
  displayLeadMs: number;
  private sampledAt = NaN;
  /** Set by `sample`: the largest gap between a joint drawn and its newest report, degrees. */
  aheadDeg = 0;

  constructor(joints: readonly JointSpec[], opts: Partial<TwinPredictorOptions> = {}) {
    this.opts = { ...DEFAULT_TWIN_PREDICTOR_OPTIONS, ...opts };
    this.clock = new ClockOffset(this.opts.clock);
    this.displayLeadMs = this.opts.displayLeadMs;
    this.configure(joints);
  }

  /** Another arm: one predictor per joint, nothing known. */
  configure(joints: readonly JointSpec[]): void {
    this.joints = joints.map(
      (j) => new JointPredictor(j.minDeg, j.maxDeg, j.maxSpeedDegPerS / 1000, this.opts.joint),
    );
    this.clock.reset();
  }

  get count(): number {
    return this.joints.length;
  }

  joint(i: number): JointPredictor | undefined {
    return this.joints[i];
  }

  /**
   * A state report's stamp arrived at page time `now` (call once per report, before its
   * joints); returns the stamp in the arm's time (its arrival on that clock when it has no `$TIM`).
   */
  arrive(stamp: number | undefined, now: number): number {
    // An unstamped report among stamped ones is put on the arm's clock as of its arrival.
    if (stamp === undefined || !Number.isFinite(stamp)) return this.armTime(now);
    this.clock.add(now, stamp);
    return stamp;
  }

  /** The arm's time at page time `now` (page time itself when no report is stamped). */
  armTime(now: number): number {
    const off = this.clock.offsetMs;
    return Number.isNaN(off) ? now : now - off;
  }

  report(i: number, stamp: number, angle: number): void {
    this.joints[i]?.report(stamp, angle);
  }

  /** A move of joint i to `targetDeg` in `durMs`, seen at page time `now`. */
  command(i: number, targetDeg: number, durMs: number, now: number): void {
    this.joints[i]?.command(targetDeg, durMs, this.armTime(now));
  }

  /** A stop of joint i (every joint when i is undefined), seen at page time `now`. */
  stop(i: number | undefined, now: number): void {
    const at = this.armTime(now);
    if (i === undefined) for (const j of this.joints) j.stop(at);
    else this.joints[i]?.stop(at);
  }

  /** Writes each joint's predicted angle at page time `now` into `out`. */
  sample(now: number, out: Float64Array): void {
    this.sampledAt = now;
    const t = this.armTime(now + this.displayLeadMs);
    let predicting = false;
    let lead = 0;
    let ahead = 0;
    for (let i = 0; i < this.joints.length && i < out.length; i++) {
      const j = this.joints[i]!;
      const v = j.predict(t);
      out[i] = v;
      const gap = Math.abs(v - j.a0);
      if (gap > ahead) ahead = gap;
      if (gap > this.opts.unconfirmedDeg) {
        predicting = true;
        if (t - j.s0 > lead) lead = t - j.s0;
      }
    }
    this.predicting = predicting;
    this.leadMs = lead;
    this.aheadDeg = ahead;
  }

  /**
   * The poses ahead of a sample, for a renderer that draws later than the page samples (the
   * render worker): `count` poses at page times `from + stepMs`, `from + 2·stepMs`, …, joint
   * after joint (`out[k·n + i]`). Each is the prediction itself (never past a target, a limit or
   * a stop), so a pose between two of them is one too. Changes nothing here.
   */
  poseAhead(from: number, stepMs: number, count: number, out: Float64Array): void {
    const n = this.joints.length;
    for (let k = 0; k < count; k++) {
      const t = this.armTime(from + (k + 1) * stepMs);
      for (let i = 0; i < n && k * n + i < out.length; i++)
        out[k * n + i] = this.joints[i]!.predict(t);
    }
  }

  /**
   * The frame of the last `sample` finished drawing at page time `now`: the pose should have
   * been predicted that much later (learnt as a moving average, bounded).
   */
  shown(now: number): void {
    const lag = now - this.sampledAt;
    this.sampledAt = NaN;
    if (!(lag >= 0 && lag <= this.opts.maxDisplayLeadMs)) return;
    this.displayLeadMs += this.opts.displayLeadSmoothing * (lag - this.displayLeadMs);
  }

  reset(): void {
    for (const j of this.joints) j.reset();
    this.clock.reset();
    this.predicting = false;
    this.leadMs = this.aheadDeg = 0;
  }
}
