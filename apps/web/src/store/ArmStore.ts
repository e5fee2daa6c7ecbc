/**
 * The HUD's plain store: everything the status stream says, held as mutable typed arrays and
 * counters. The MQTT link feeds it (`ingest`), the three.js loop reads the drawn angles every
 * frame (`sample`, then `rendered`), the health charts read `history`, and React panels read
 * its fields through `useSampled` a few times a second. No message causes a React render, and
 * nothing here allocates per frame. Every method takes `now` (a monotonic ms clock,
 * performance.now() in the page) so tests drive time themselves.
 */
import {
  PWM_CENTRE,
  US_PER_DEG,
  angleFromPwm,
  createReader,
  unhandled,
  type Frame,
  type Group,
  type Reader,
} from '@armtwin/protocol';
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';
import { HealthHistory } from './HealthHistory.ts';
import { DEFAULT_THERMAL_PARAMS, ThermalWatch, type ThermalWatchOptions } from '@armtwin/protocol';
import { IntervalEstimator, JointTween } from './interpolation.ts';
import { TwinPredictor, type TwinMode, type TwinPredictorOptions } from './TwinPredictor.ts';
import { TrackingErrors } from './trackingError.ts';
import { RateMeter } from './RateMeter.ts';
import { PingTracker } from './PingTracker.ts';
import {
  countDrop,
  emptyDropCounters,
  type DropCounters,
  type FirstErrors,
} from './readerErrors.ts';

export interface ArmStoreOptions {
  /** The arm's profile: servo count, names, polarity. */
  arm: ArmProfile;
  /** The seed's α: > 1 reaches each reported pose sooner, < 1 later (smoother, laggier). */
  interpolationAlpha: number;
  /** Health rows kept for the strip charts (at 2 Hz, 240 = two minutes). */
  historyLength: number;
  /** No state report for longer than this, ms, and the data is stale. */
  staleAfterMs: number;
  /**
   * State reports per second (over the last second) from which each report is drawn as it is,
   * not tweened: reports then come faster than frames, and a tween toward the newest one only
   * lags behind it (by up to a report interval, more when a busy page takes several reports at
   * once). Below it, reports are interpolated (a 5 Hz arm glides).
   */
  drawNewestAboveHz: number;
  /**
   * How the arm is drawn: `predict` (where it is at the display instant, from its reports,
   * their `$TIM` and what was commanded: ./TwinPredictor.ts), `interpolate` (the seed's tween
   * toward each report, drawn as it is above `drawNewestAboveHz`) or `newest` (each report as it is).
   */
  twinMode: TwinMode;
  predictor: Partial<TwinPredictorOptions>;
  /** The thermal early warning's settings (@armtwin/protocol `DEFAULT_THERMAL_WATCH_OPTIONS`). */
  thermal: Partial<ThermalWatchOptions>;
}

export const DEFAULT_ARM_STORE_OPTIONS: ArmStoreOptions = {
  arm: DEMO_ARM,
  interpolationAlpha: 1,
  historyLength: 240,
  staleAfterMs: 1000,
  drawNewestAboveHz: 100,
  twinMode: 'predict',
  predictor: {},
  thermal: {},
};

export type ConnectionState =
  'idle' | 'connecting' | 'connected' | 'reconnecting' | 'offline' | 'error';

export interface StoreCounters extends DropCounters {
  /** MQTT messages on the status topic. */
  messages: number;
  /** Frames decoded (group members included). */
  frames: number;
  /** `$ERR` frames from the controller. */
  controllerErrors: number;
  /** Messages this HUD published on the control topic. */
  published: number;
}

export class ArmStore {
  readonly opts: ArmStoreOptions;
  // The per-servo arrays are replaced (never resized) by `configure`, when the arm's profile
  // changes; read them through the store each time, never keep one.
  servoCount!: number;
  /**
   * Latest reported pulse per servo, NaN until reported. For a servo that reports §8 angle
   * frames, the exact pulse-equivalent of its angle (unrounded and unclamped, so linear in the
   * angle and outside 500–2500 µs beyond ±135°), for the panels that count in pulses.
   */
  pwm!: Float64Array;
  /**
   * Latest reported servo angle per servo, degrees in the store arm's terms, NaN until
   * reported: an angle frame's angle as it came, or a pulse frame's pulse as an angle. When a
   * servo is reported both ways, the newer report wins (both are its position).
   */
  angle!: Float64Array;
  /** Servo angles drawn this frame, degrees (written by `sample`). Read by the debug hook. */
  rendered!: Float64Array;
  /** Last pulse this HUD commanded per servo (jog or IK), NaN = none / follow the arm. */
  commandedPwm!: Float64Array;
  /** Latest temperature (°C) and supply voltage (mV) per servo, NaN until reported. */
  temp!: Float64Array;
  mv!: Float64Array;
  history!: HealthHistory;
  /**
   * Each servo's thermal model, fed every position and health report: the predicted temperature
   * (drawn dashed beside the measured) and the early warning before 60 °C. Generic parameters
   * until the Health panel loads a fit from the arm's history (`setParams`).
   */
  thermal!: ThermalWatch;
  /** Each joint's commanded-vs-reported error, updated by `sample` (the links' paint). */
  tracking!: TrackingErrors;
  /** Bumped by `configure`: the servo list changed. */
  armVersion = 0;
  readonly counters: StoreCounters;
  readonly ping = new PingTracker();
  connection: ConnectionState = 'idle';
  connectionError = '';
  /** Retained `arm/{id}/online`: true, false, or null before it is known. */
  armOnline: boolean | null = null;
  /** The retained online payload when it was neither `1` nor `0` (shown as text), else ''. */
  armOnlineText = '';
  /** When the last state report arrived (ms), NaN = never. */
  lastStateAt = NaN;
  /** The newest `$TIM` (epoch ms) of a state report taken in, NaN = none stamped yet. */
  lastStateStamp = NaN;
  /** Last `$KMS:c!` reply and how many replies have come (so a panel sees a new one). */
  kmsReply: number | null = null;
  kmsReplies = 0;
  lastControllerError = '';
  /** First message per reader error kind, for the Status panel. */
  readonly firstError: FirstErrors = {};

  private tweens!: JointTween[];
  /** The predictive twin (`twinMode` 'predict'); fed every report and every command seen. */
  readonly predictor: TwinPredictor;
  /** The arm-time stamp of the state report being taken in. */
  private reportStamp = NaN;
  private readonly controlReader: Reader;
  private readonly interval = new IntervalEstimator();
  private readonly messageRate = new RateMeter();
  private readonly stateRate = new RateMeter();
  private readonly reader: Reader;
  private rowTemp!: Float64Array;
  private rowVolt!: Float64Array;
  private rowPredicted!: Float64Array;
  private drawn!: Float64Array;
  private now = 0;
  /** Whether the stream is fast enough to draw each report as it is (`drawNewestAboveHz`). */
  private drawNewest = false;

  constructor(opts: Partial<ArmStoreOptions> = {}) {
    this.opts = { ...DEFAULT_ARM_STORE_OPTIONS, ...opts };
    this.predictor = new TwinPredictor(this.opts.arm.servos, this.opts.predictor);
    this.allocate();
    this.counters = {
      messages: 0,
      frames: 0,
      ...emptyDropCounters(),
      controllerErrors: 0,
      published: 0,
    };
    this.reader = createReader({
      onFrame: (f) => this.onFrame(f),
      onGroup: (g) => this.onGroup(g),
      onError: (e) => countDrop(this.counters, this.firstError, e),
    });
    this.controlReader = createReader({
      onFrame: (f) => this.onCommand(f),
      onGroup: (g) => {
        for (const f of g.frames) this.onCommand(f);
      },
    });
  }

  private allocate(): void {
    const n = (this.servoCount = this.opts.arm.servos.length);
    this.pwm = new Float64Array(n).fill(NaN);
    this.angle = new Float64Array(n).fill(NaN);
    this.rendered = new Float64Array(n).fill(NaN);
    this.commandedPwm = new Float64Array(n).fill(NaN);
    this.temp = new Float64Array(n).fill(NaN);
    this.mv = new Float64Array(n).fill(NaN);
    this.rowTemp = new Float64Array(n);
    this.rowVolt = new Float64Array(n);
    this.drawn = new Float64Array(n).fill(NaN);
    this.tweens = Array.from({ length: n }, () => new JointTween());
    this.predictor.configure(this.opts.arm.servos);
    const setting = this.tracking?.setting ?? 'auto';
    this.tracking = new TrackingErrors(n);
    this.tracking.setting = setting;
    this.history = new HealthHistory(n, this.opts.historyLength);
    this.thermal = new ThermalWatch(
      this.opts.arm.servos.map(() => DEFAULT_THERMAL_PARAMS),
      this.opts.thermal,
    );
    this.rowPredicted = new Float64Array(n);
  }

  /**
   * Another arm profile (the selected arm announced a different robot): new per-servo arrays
   * sized for it, the arm's data forgotten (as `resetArm`) except whether it is online (the
   * retained message came once). Counters are kept.
   */
  configure(arm: ArmProfile): void {
    const { armOnline, armOnlineText } = this;
    this.opts.arm = arm;
    this.allocate();
    this.resetArm();
    this.armOnline = armOnline;
    this.armOnlineText = armOnlineText;
    this.armVersion++;
  }

  /** One MQTT message from `arm/{id}/status`, received at `now`. */
  ingest(payload: string | Uint8Array, now: number): void {
    this.now = now;
    this.counters.messages++;
    this.messageRate.add(now);
    this.reader.feed(payload);
    // A `$TIM` stamps only the frames of its own payload.
    this.reader.clearStamp();
  }

  /**
   * Commands on the arm's control topics (this page's own and, where the broker lets the page
   * read them, everyone's), seen at `now`: the predictor's idea of where each joint is heading.
   */
  noteControl(payload: string | Uint8Array, now: number): void {
    this.now = now;
    this.controlReader.feed(payload);
    this.controlReader.clearStamp();
  }

  private onCommand(f: Frame): void {
    const servos = this.opts.arm.servos;
    if (f.type === 'move' && f.id < this.servoCount)
      this.predictor.command(f.id, angleFromPwm(f.pwm, servos[f.id]!.polarity), f.ms, this.now);
    else if (f.type === 'angleMove' && f.id < this.servoCount)
      this.predictor.command(f.id, f.deg, f.ms, this.now);
    else if (f.type === 'stop') this.predictor.stop(f.id === 255 ? undefined : f.id, this.now);
  }

  private onGroup(g: Group): void {
    let positions = 0;
    let health = 0;
    this.rowTemp.fill(NaN);
    this.rowVolt.fill(NaN);
    this.counters.frames += g.frames.length;
    for (const f of g.frames) {
      if (f.type === 'position') {
        if (positions++ === 0) this.stateArrived(g.time);
        this.setPosition(f.id, f.pwm);
      } else if (f.type === 'angle') {
        if (positions++ === 0) this.stateArrived(g.time);
        this.setAngle(f.id, f.deg);
      } else if (f.type === 'health') {
        health++;
        this.setHealth(f.id, f.temp, f.mv);
      } else {
        this.handle(f);
      }
    }
    if (health > 0) this.pushHealthRow(g.time);
  }

  private onFrame(f: Frame): void {
    this.counters.frames++;
    this.handle(f);
  }

  private handle(f: Frame): void {
    switch (f.type) {
      case 'position':
        this.stateArrived(f.time);
        this.setPosition(f.id, f.pwm);
        break;
      case 'angle':
        this.stateArrived(f.time);
        this.setAngle(f.id, f.deg);
        break;
      case 'health':
        this.rowTemp.fill(NaN);
        this.rowVolt.fill(NaN);
        this.setHealth(f.id, f.temp, f.mv);
        this.pushHealthRow(f.time);
        break;
      case 'kmsResult':
        this.kmsReply = f.code;
        this.kmsReplies++;
        break;
      case 'ping':
        this.ping.echo(f.seq, this.now);
        break;
      case 'controllerError':
        this.counters.controllerErrors++;
        this.lastControllerError = f.text;
        break;
      // `$TIM` stamps the frames after it (the reader does that), and host → arm frames
      // someone else published on the status topic say nothing about the arm.
      case 'time':
      case 'move':
      case 'angleMove':
      case 'readPosition':
      case 'readHealth':
      case 'stop':
      case 'kms':
        break;
      default:
        return unhandled(f);
    }
  }

  private stateArrived(stamp: number | undefined): void {
    this.lastStateAt = this.now;
    this.reportStamp = this.predictor.arrive(stamp, this.now);
    if (stamp !== undefined && !(stamp <= this.lastStateStamp)) this.lastStateStamp = stamp;
    this.stateRate.add(this.now);
    this.interval.arrive(this.now);
    this.drawNewest = this.stateRate.rate(this.now) >= this.opts.drawNewestAboveHz;
  }

  private setPosition(id: number, pwm: number): void {
    if (id >= this.servoCount) return;
    this.pwm[id] = pwm;
    this.retarget(id, angleFromPwm(pwm, this.opts.arm.servos[id]!.polarity));
  }

  /** An angle report (§8): drawn as it came, with no pulse on the way (±360° stays ±360°). */
  private setAngle(id: number, deg: number): void {
    if (id >= this.servoCount) return;
    this.pwm[id] = PWM_CENTRE + this.opts.arm.servos[id]!.polarity * US_PER_DEG * deg;
    this.retarget(id, deg);
  }

  private retarget(id: number, deg: number): void {
    this.angle[id] = deg;
    this.thermal.position(id, deg);
    this.predictor.report(id, this.reportStamp, deg);
    this.tweens[id]!.retarget(
      deg,
      this.now,
      this.drawNewest ? 0 : this.interval.intervalMs,
      this.opts.interpolationAlpha,
    );
  }

  private setHealth(id: number, temp: number, mv: number): void {
    if (id >= this.servoCount) return;
    this.temp[id] = temp;
    this.mv[id] = mv;
    this.rowTemp[id] = temp;
    this.rowVolt[id] = mv / 1000;
  }

  private pushHealthRow(stamp: number | undefined): void {
    const t = stamp ?? Date.now();
    this.rowPredicted.fill(NaN);
    for (let i = 0; i < this.servoCount; i++) {
      if (Number.isNaN(this.rowTemp[i]!)) continue;
      this.thermal.health(i, t, this.rowTemp[i]!);
      this.rowPredicted[i] = this.thermal.state(i)!.predictedC;
    }
    this.history.push(t / 1000, this.rowTemp, this.rowVolt, this.rowPredicted);
  }

  /**
   * Fills `rendered` with the servo angles to draw at `now` (as `twinMode` says); true if any
   * changed. In `predict` mode, `predicting` and `predictionLeadMs` then say whether the pose
   * is ahead of every report.
   */
  sample(now: number): boolean {
    let changed = false;
    const alpha = this.opts.interpolationAlpha;
    const mode = this.opts.twinMode;
    if (mode === 'predict') this.predictor.sample(now, this.drawn);
    this.updateTracking();
    for (let i = 0; i < this.servoCount; i++) {
      const v =
        mode === 'predict'
          ? this.drawn[i]!
          : mode === 'newest'
            ? this.angle[i]!
            : this.tweens[i]!.valueAt(now, alpha);
      if (v !== this.rendered[i] && !(Number.isNaN(v) && Number.isNaN(this.rendered[i]!))) {
        this.rendered[i] = v;
        changed = true;
      }
    }
    return changed;
  }

  /**
   * Tracking error per joint: the reported angle against the command's course at the same
   * instant (./trackingError.ts); without a course seen, against this HUD's commanded pulse
   * once the joint has stopped moving.
   */
  private updateTracking(): void {
    const servos = this.opts.arm.servos;
    for (let i = 0; i < this.servoCount; i++) {
      const j = this.predictor.joint(i);
      if (!j) continue;
      let commanded = j.commandedAt(j.s0);
      const pwm = this.commandedPwm[i]!;
      if (Number.isNaN(commanded) && Number.isFinite(pwm) && j.reportVelocity() === 0)
        commanded = angleFromPwm(pwm, servos[i]!.polarity);
      this.tracking.set(i, commanded, this.angle[i]!);
    }
  }

  /** The pose drawn by the last `sample` is a prediction that no report has confirmed yet. */
  get predicting(): boolean {
    return this.opts.twinMode === 'predict' && this.predictor.predicting;
  }

  /** How far the predicted pose is ahead of the newest report, ms (0 when not predicting). */
  get predictionLeadMs(): number {
    return this.predicting ? this.predictor.leadMs : 0;
  }

  /** The frame drawn from the last `sample` is done at `now` (the predictor learns the lag). */
  frameShown(now: number): void {
    this.predictor.shown(now);
  }

  setTwinMode(mode: TwinMode): void {
    this.opts.twinMode = mode;
  }

  /** No state report for longer than `staleAfterMs` (or none yet). */
  isStale(now: number): boolean {
    return !(now - this.lastStateAt <= this.opts.staleAfterMs);
  }

  /** Messages and state reports per second over the last second. */
  messageRatePerS(now: number): number {
    return this.messageRate.rate(now);
  }
  stateRatePerS(now: number): number {
    return this.stateRate.rate(now);
  }

  get expectedStateIntervalMs(): number {
    return this.interval.intervalMs;
  }

  setInterpolationAlpha(alpha: number): void {
    if (alpha > 0 && Number.isFinite(alpha)) this.opts.interpolationAlpha = alpha;
  }

  /** Forgets the arm: a new arm id or broker. Counters are kept (they are per page). */
  resetArm(): void {
    this.reader.reset();
    this.pwm.fill(NaN);
    this.angle.fill(NaN);
    this.rendered.fill(NaN);
    this.commandedPwm.fill(NaN);
    this.temp.fill(NaN);
    this.mv.fill(NaN);
    for (const t of this.tweens) t.reset();
    this.predictor.reset();
    this.thermal.reset();
    this.tracking.reset();
    this.controlReader.reset();
    this.interval.reset();
    this.messageRate.reset();
    this.stateRate.reset();
    this.history.clear();
    this.ping.reset();
    this.armOnline = null;
    this.armOnlineText = '';
    this.lastStateAt = NaN;
    this.lastStateStamp = NaN;
    this.kmsReply = null;
    this.drawNewest = false;
  }
}
