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
import { IntervalEstimator, JointTween } from './interpolation.ts';
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
}

export const DEFAULT_ARM_STORE_OPTIONS: ArmStoreOptions = {
  arm: DEMO_ARM,
  interpolationAlpha: 1,
  historyLength: 240,
  staleAfterMs: 1000,
  drawNewestAboveHz: 100,
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
  private readonly interval = new IntervalEstimator();
  private readonly messageRate = new RateMeter();
  private readonly stateRate = new RateMeter();
  private readonly reader: Reader;
  private rowTemp!: Float64Array;
  private rowVolt!: Float64Array;
  private now = 0;
  /** Whether the stream is fast enough to draw each report as it is (`drawNewestAboveHz`). */
  private drawNewest = false;

  constructor(opts: Partial<ArmStoreOptions> = {}) {
    this.opts = { ...DEFAULT_ARM_STORE_OPTIONS, ...opts };
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
    this.tweens = Array.from({ length: n }, () => new JointTween());
    this.history = new HealthHistory(n, this.opts.historyLength);
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
    this.history.push((stamp ?? Date.now()) / 1000, this.rowTemp, this.rowVolt);
  }

  /** Fills `rendered` with the interpolated servo angles at `now`; true if any changed. */
  sample(now: number): boolean {
    let changed = false;
    const alpha = this.opts.interpolationAlpha;
    for (let i = 0; i < this.servoCount; i++) {
      const v = this.tweens[i]!.valueAt(now, alpha);
      if (v !== this.rendered[i] && !(Number.isNaN(v) && Number.isNaN(this.rendered[i]!))) {
        this.rendered[i] = v;
        changed = true;
      }
    }
    return changed;
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
