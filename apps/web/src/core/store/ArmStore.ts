/**
 * The HUD's plain store: everything the status stream says, held as mutable typed arrays and
 * counters. The MQTT link feeds it (`ingest`), the three.js loop reads the drawn angles every
 * frame (`sample`, then `rendered`), the health charts read `history`, and React panels read
 * its fields through `useSampled` a few times a second. No message causes a React render, and
 * nothing here allocates per frame. Every method takes `now` (a monotonic ms clock,
 * performance.now() in the page) so tests drive time themselves. Its parts: the status and
 * control readers (./statusReader.ts, ./commandReader.ts), the health row (./HealthRow.ts), the
 * tweens and the predictor that draw the arm (./PoseTweens.ts, ./TwinPredictor.ts), the joints'
 * tracking error (./trackJoints.ts), its settings (./armStoreOptions.ts).
 */
import { PWM_CENTRE, US_PER_DEG, angleFromPwm, type Reader } from '@armtwin/protocol';
import type { ArmProfile } from '@armtwin/ik';
import { HealthHistory } from './HealthHistory.ts';
import { HealthRow } from './HealthRow.ts';
import { DEFAULT_THERMAL_PARAMS, ThermalWatch } from '@armtwin/thermal';
import { PoseTweens } from './PoseTweens.ts';
import { TwinPredictor, type TwinMode } from './TwinPredictor.ts';
import { TrackingErrors } from './trackingError.ts';
import { trackJoints } from './trackJoints.ts';
import { createCommandReader } from './commandReader.ts';
import { servoSlots } from './servoSlots.ts';
import { createStatusReader } from './statusReader.ts';
import { RateMeter } from './RateMeter.ts';
import { PingTracker } from './PingTracker.ts';
import { countDrop, type FirstErrors } from './readerErrors.ts';
import {
  DEFAULT_ARM_STORE_OPTIONS,
  emptyStoreCounters,
  type ArmStoreOptions,
  type ConnectionState,
  type StoreCounters,
} from './armStoreOptions.ts';

export {
  DEFAULT_ARM_STORE_OPTIONS,
  type ArmStoreOptions,
  type ConnectionState,
  type StoreCounters,
} from './armStoreOptions.ts';

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

  /** The `interpolate` mode's tweens toward each report. */
  private tweens!: PoseTweens;
  /** The predictive twin (`twinMode` 'predict'); fed every report and every command seen. */
  readonly predictor: TwinPredictor;
  /** The arm-time stamp of the state report being taken in. */
  private reportStamp = NaN;
  private readonly controlReader: Reader;
  private readonly messageRate = new RateMeter();
  private readonly stateRate = new RateMeter();
  private readonly reader: Reader;
  /** The health row of the report being taken in. */
  private row!: HealthRow;
  private drawn!: Float64Array;
  /** Frame id → slot (./servoSlots.ts). */
  private slots!: Int16Array;
  private now = 0;

  constructor(opts: Partial<ArmStoreOptions> = {}) {
    this.opts = { ...DEFAULT_ARM_STORE_OPTIONS, ...opts };
    this.predictor = new TwinPredictor(this.opts.arm.servos, this.opts.predictor);
    this.allocate();
    this.counters = emptyStoreCounters();
    this.reader = createStatusReader(
      {
        counted: (n) => (this.counters.frames += n),
        stateArrived: (stamp) => this.stateArrived(stamp),
        position: (id, pwm) => this.setPosition(id, pwm),
        angle: (id, deg) => this.setAngle(id, deg),
        healthRow: () => this.row.clear(),
        health: (id, temp, mv) => this.setHealth(id, temp, mv),
        healthDone: (stamp) => this.row.push(stamp, this.thermal, this.history),
        kmsResult: (code) => {
          this.kmsReply = code;
          this.kmsReplies++;
        },
        ping: (seq) => this.ping.echo(seq, this.now),
        controllerError: (text) => {
          this.counters.controllerErrors++;
          this.lastControllerError = text;
        },
      },
      (e) => countDrop(this.counters, this.firstError, e),
    );
    this.controlReader = createCommandReader(
      this.predictor,
      () => this.opts.arm,
      (id) => this.slot(id),
      () => this.now,
    );
  }

  private allocate(): void {
    const n = (this.servoCount = this.opts.arm.servos.length);
    this.slots = servoSlots(this.opts.arm.servos);
    this.pwm = new Float64Array(n).fill(NaN);
    this.angle = new Float64Array(n).fill(NaN);
    this.rendered = new Float64Array(n).fill(NaN);
    this.commandedPwm = new Float64Array(n).fill(NaN);
    this.temp = new Float64Array(n).fill(NaN);
    this.mv = new Float64Array(n).fill(NaN);
    this.row = new HealthRow(n);
    this.drawn = new Float64Array(n).fill(NaN);
    this.tweens = new PoseTweens(n);
    this.predictor.configure(this.opts.arm.servos);
    const setting = this.tracking?.setting ?? 'auto';
    this.tracking = new TrackingErrors(n);
    this.tracking.setting = setting;
    this.history = new HealthHistory(n, this.opts.historyLength);
    this.thermal = new ThermalWatch(
      this.opts.arm.servos.map(() => DEFAULT_THERMAL_PARAMS),
      this.opts.thermal,
    );
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

  private stateArrived(stamp: number | undefined): void {
    this.lastStateAt = this.now;
    this.reportStamp = this.predictor.arrive(stamp, this.now);
    if (stamp !== undefined && !(stamp <= this.lastStateStamp)) this.lastStateStamp = stamp;
    this.stateRate.add(this.now);
    this.tweens.arrive(this.now, this.stateRate.rate(this.now), this.opts.drawNewestAboveHz);
  }

  /** The slot (profile index) of the servo a frame names by `id`; -1 if the arm has none. */
  private slot(id: number): number {
    return this.slots[id] ?? -1;
  }

  /** This HUD commanded servo `id` (a frame's id, not a slot) to `pwm`; NaN: follow the arm. */
  setCommanded(id: number, pwm: number): void {
    const i = this.slot(id);
    if (i >= 0) this.commandedPwm[i] = pwm;
  }

  private setPosition(id: number, pwm: number): void {
    const i = this.slot(id);
    if (i < 0) return;
    this.pwm[i] = pwm;
    this.retarget(i, angleFromPwm(pwm, this.opts.arm.servos[i]!.polarity));
  }

  /** An angle report (§8): drawn as it came, with no pulse on the way (±360° stays ±360°). */
  private setAngle(id: number, deg: number): void {
    const i = this.slot(id);
    if (i < 0) return;
    this.pwm[i] = PWM_CENTRE + this.opts.arm.servos[i]!.polarity * US_PER_DEG * deg;
    this.retarget(i, deg);
  }

  /** Servo `i` (a slot) reported at `deg`. */
  private retarget(i: number, deg: number): void {
    this.angle[i] = deg;
    this.thermal.position(i, deg);
    this.predictor.report(i, this.reportStamp, deg);
    this.tweens.retarget(i, deg, this.now, this.opts.interpolationAlpha);
  }

  private setHealth(id: number, temp: number, mv: number): void {
    const i = this.slot(id);
    if (i < 0) return;
    this.temp[i] = temp;
    this.mv[i] = mv;
    this.row.set(i, temp, mv);
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
    trackJoints(this.tracking, this.predictor, this.opts.arm.servos, this.commandedPwm, this.angle);
    for (let i = 0; i < this.servoCount; i++) {
      const v =
        mode === 'predict'
          ? this.drawn[i]!
          : mode === 'newest'
            ? this.angle[i]!
            : this.tweens.valueAt(i, now, alpha);
      if (v !== this.rendered[i] && !(Number.isNaN(v) && Number.isNaN(this.rendered[i]!))) {
        this.rendered[i] = v;
        changed = true;
      }
    }
    return changed;
  }

  /** The pose drawn by the last `sample` is a prediction that no report has confirmed yet. */
  get predicting(): boolean {
    return this.opts.twinMode === 'predict' && this.predictor.predicting;
  }

  /**
   * How far the predicted pose is ahead of the newest report, ms (0 when not predicting): the
   * sample's lead (the renderer's own, where it draws later along the course, is in its reports:
   * scene/render/SceneReports.ts).
   */
  get predictionLeadMs(): number {
    return this.predicting ? this.predictor.leadMs : 0;
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
    return this.tweens.intervalMs;
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
    this.tweens.reset();
    this.predictor.reset();
    this.thermal.reset();
    this.tracking.reset();
    this.controlReader.reset();
    this.messageRate.reset();
    this.stateRate.reset();
    this.history.clear();
    this.ping.reset();
    this.armOnline = null;
    this.armOnlineText = '';
    this.lastStateAt = NaN;
    this.lastStateStamp = NaN;
    this.kmsReply = null;
  }
}
