/**
 * The simulated controller: executes control frames the way the firmware would, against the
 * servo model. Pure: time comes in as an argument (epoch ms), replies go out as encoded frame
 * strings appended to an array the caller owns. The MQTT or serial side lives elsewhere.
 */
import { speaksAngle, type ArmProfile } from '@armtwin/ik';
import {
  KMS_FLOOR_CODE,
  KMS_ZONE_CODE,
  PWM_CENTRE,
  PWM_MAX,
  PWM_MIN,
  SERVO_ID_ALL,
  US_PER_DEG,
  encodeAngle,
  encodeControllerError,
  encodeGroup,
  encodeHealth,
  encodeKmsResult,
  encodePing,
  encodePosition,
  unhandled,
  type Frame,
  type Group,
} from '@armtwin/protocol';
import { DEFAULT_SIM_MODEL_OPTIONS, reportAngle, type SimModelOptions } from './options.ts';
import { solveKms } from './kms.ts';
import { Servos } from './servos.ts';
import { keepOutKind } from '@armtwin/motion';

import { frameRefusal, id3 } from './frameRefusal.ts';

/** What the controller did with a command, counted by kind. */
export interface SimCounters {
  moves: number;
  groups: number;
  kms: number;
  stops: number;
  emergencyStops: number;
  rejected: Record<
    'limit' | 'floor' | 'zone' | 'unknown-servo' | 'group' | 'unexpected' | 'ik',
    number
  >;
}

export class SimModel {
  readonly servos: Servos;
  readonly arm: ArmProfile;
  readonly counters: SimCounters = {
    moves: 0,
    groups: 0,
    kms: 0,
    stops: 0,
    emergencyStops: 0,
    rejected: { limit: 0, floor: 0, zone: 0, 'unknown-servo': 0, group: 0, unexpected: 0, ik: 0 },
  };

  /** Why the last move refused by a keep-out rule was refused ('' = none yet). */
  lastKeepOutRefusal = '';
  private readonly kmsSolver: SimModelOptions['kms'];
  private keepOut: SimModelOptions['keepOut'];
  /** Per servo index: 1 when its position is reported in §8 angle frames. */
  readonly reportsAngle: Uint8Array;
  /** Per servo index: mounting polarity, for servo angle ↔ the model's pulse-equivalent. */
  private readonly polarity: Float64Array;

  constructor(options: Partial<SimModelOptions> = {}, now = 0) {
    const o = { ...DEFAULT_SIM_MODEL_OPTIONS, ...options };
    this.arm = o.arm;
    this.kmsSolver = o.kms;
    this.keepOut = o.keepOut;
    this.servos = new Servos(o, now);
    this.reportsAngle = Uint8Array.from(o.arm.servos, (spec) =>
      reportAngle(o.report, speaksAngle(spec)) ? 1 : 0,
    );
    this.polarity = Float64Array.from(o.arm.servos, (spec) => spec.polarity);
  }

  /** Integrates heat and supply up to t; call with each state tick and before each command. */
  advance(t: number): void {
    this.servos.advance(t);
  }

  /** Rounded pulse width of the servo at index i at time t. */
  pwmAt(i: number, t: number): number {
    return Math.round(this.servos.pwmAt(i, t));
  }

  /**
   * Servo angle of the servo at index i at time t, degrees: exact (the model's positions are
   * unrounded pulse-equivalents, linear in the angle and never clamped to the pulse range).
   */
  angleAt(i: number, t: number): number {
    return (this.polarity[i]! * (this.servos.pwmAt(i, t) - PWM_CENTRE)) / US_PER_DEG;
  }

  /** The model's (unrounded) pulse-equivalent of servo angle `deg` for the servo at index i. */
  private pulseOfAngle(i: number, deg: number): number {
    return PWM_CENTRE + this.polarity[i]! * deg * US_PER_DEG;
  }

  /**
   * The pulse a position report carries: rounded, and held within 500–2500 µs (only an angle
   * servo reported in pulses, `report: 'pulse'`, can be outside it).
   */
  reportedPwm(i: number, t: number): number {
    return Math.min(PWM_MAX, Math.max(PWM_MIN, this.pwmAt(i, t)));
  }

  /** The position report of the servo at index i at t: `#IIIA±ddd.dd!` or `#IIIPpppp!`. */
  positionReport(i: number, t: number): string {
    const id = this.servos.ids[i]!;
    return this.reportsAngle[i]
      ? encodeAngle(id, this.angleAt(i, t))
      : encodePosition(id, this.reportedPwm(i, t));
  }

  /** Executes one top-level frame received at t; appends reply frames to `out`. */
  execute(frame: Frame, t: number, out: string[]): void {
    this.advance(t);
    const reads: string[] = [];
    const error = this.check(frame) || this.checkKeepOut([frame]);
    if (error) {
      out.push(encodeControllerError(error));
      return;
    }
    this.apply(frame, t, reads, out);
    if (reads.length > 1) out.push(encodeGroup(reads));
    else if (reads.length === 1) out.push(reads[0]!);
  }

  /**
   * Executes a `{…}` group received at t: only when every frame in it decoded and passes its
   * checks, and then all together. Reads inside it are answered as one group.
   */
  executeGroup(group: Group, t: number, out: string[]): void {
    this.advance(t);
    let error = group.invalid > 0 ? `group rejected: ${group.invalid} bad frame(s)` : '';
    for (const frame of group.frames) {
      if (error) break;
      const e = this.check(frame);
      if (e) error = `group rejected: ${e}`;
    }
    if (!error) {
      const e = this.checkKeepOut(group.frames);
      if (e) error = `group rejected: ${e}`;
    }
    if (error) {
      this.counters.rejected.group++;
      out.push(encodeControllerError(error));
      return;
    }
    this.counters.groups++;
    const reads: string[] = [];
    for (const frame of group.frames) this.apply(frame, t, reads, out);
    if (reads.length > 0) out.push(encodeGroup(reads));
  }

  /** Puts other keep-out rules in force (a profile file edited while running: zones-follow.ts). */
  setKeepOut(check: SimModelOptions['keepOut']): void {
    this.keepOut = check;
  }

  /** Stops every servo where it is now (`#255PDST!`). */
  emergencyStop(t: number): void {
    this.advance(t);
    this.counters.emergencyStops++;
    for (let i = 0; i < this.servos.count; i++) this.servos.stop(i, t);
  }

  /**
   * Puts servos at a pose at once, at rest (`pulses`: servo id → pulse width, µs, in the units
   * of a `#IIIPpppp!` move); every other servo stops where it is. Each pulse is held within its
   * servo's limits; the keep-out rules are not asked (a pose is where an arm is, not a move).
   * Returns the pulses placed by servo id. Throws, changing nothing, for a servo the arm lacks
   * or a pulse that is not a finite number.
   */
  placeAt(pulses: ReadonlyMap<number, number>, t: number): Map<number, number> {
    const s = this.servos;
    for (const [id, pwm] of pulses) {
      if (s.indexOf(id) < 0) throw new RangeError(`no servo ${id3(id)}`);
      if (!Number.isFinite(pwm)) throw new RangeError(`servo ${id3(id)}: ${pwm} is not a pulse`);
    }
    this.advance(t);
    for (let i = 0; i < s.count; i++) s.stop(i, t);
    const placed = new Map<number, number>();
    for (const [id, pwm] of pulses) {
      const i = s.indexOf(id);
      const p = Math.min(s.maxPwm[i]!, Math.max(s.minPwm[i]!, pwm));
      s.place(i, p, t);
      placed.set(id, p);
    }
    return placed;
  }

  /** The reason a frame cannot run, or '' when it can (./frameRefusal.ts), counted by kind. */
  private check(frame: Frame): string {
    const r = frameRefusal(frame, this.servos, this.arm);
    if (!r) return '';
    this.counters.rejected[r.kind]++;
    return r.reason;
  }

  /**
   * The keep-out rules (the floor, the zones) for the move these (already checked) frames start:
   * '' when it may run, else the reason (counted as `floor` or `zone`). Changes nothing.
   */
  private checkKeepOut(frames: readonly Frame[]): string {
    if (!this.keepOut) return '';
    const s = this.servos;
    const to = Array.from(s.to);
    let moved = false;
    for (const f of frames) {
      if (f.type !== 'move' && f.type !== 'angleMove') continue;
      for (let i = 0; i < s.count; i++) {
        if (f.id !== SERVO_ID_ALL && f.id !== s.ids[i]) continue;
        to[i] = f.type === 'move' ? f.pwm : this.pulseOfAngle(i, f.deg);
        moved = true;
      }
    }
    const reason = moved ? this.keepOut(Array.from(s.to), to) : '';
    if (reason) {
      this.counters.rejected[keepOutKind(reason)]++;
      this.lastKeepOutRefusal = reason;
    }
    return reason;
  }

  /** Runs a checked frame. Position and health reads go to `reads`, other replies to `out`. */
  private apply(frame: Frame, t: number, reads: string[], out: string[]): void {
    const s = this.servos;
    switch (frame.type) {
      case 'move':
        this.counters.moves++;
        for (let i = 0; i < s.count; i++) {
          if (frame.id === SERVO_ID_ALL || frame.id === s.ids[i])
            s.moveTo(i, frame.pwm, frame.ms, t);
        }
        return;
      case 'angleMove':
        this.counters.moves++;
        for (let i = 0; i < s.count; i++) {
          if (frame.id === SERVO_ID_ALL || frame.id === s.ids[i])
            s.moveTo(i, this.pulseOfAngle(i, frame.deg), frame.ms, t);
        }
        return;
      case 'stop':
        if (frame.id === SERVO_ID_ALL) return this.emergencyStop(t);
        this.counters.stops++;
        return s.stop(s.indexOf(frame.id), t);
      case 'readPosition':
      case 'readHealth':
        for (let i = 0; i < s.count; i++) {
          const id = s.ids[i]!;
          if (frame.id !== SERVO_ID_ALL && frame.id !== id) continue;
          reads.push(
            frame.type === 'readPosition'
              ? this.positionReport(i, t)
              : encodeHealth(id, s.temp[i]!, s.mv[i]!),
          );
        }
        return;
      case 'kms':
        return this.kms(frame.x, frame.y, frame.z, frame.alpha, frame.ms, t, out);
      case 'ping':
        out.push(encodePing(frame.seq));
        return;
      case 'time': // `$TIM` on control: a stamp, nothing to do
      case 'position': // status frames never pass check()
      case 'angle':
      case 'health':
      case 'kmsResult':
      case 'controllerError':
        return;
      default:
        return unhandled(frame);
    }
  }

  /**
   * The `$KMS` code the keep-out rules give a solution (pulses by servo index, NaN = leave):
   * 0 when it may run, `KMS_FLOOR_CODE` below the floor, `KMS_ZONE_CODE` into a zone.
   */
  private kmsKeepOutCode(pwm: readonly number[]): number {
    if (!this.keepOut) return 0;
    const from = Array.from(this.servos.to);
    const to = from.map((p, i) => (Number.isNaN(pwm[i]) || pwm[i] === undefined ? p : pwm[i]!));
    const reason = this.keepOut(from, to);
    if (!reason) return 0;
    const kind = keepOutKind(reason);
    this.counters.rejected[kind]++;
    this.lastKeepOutRefusal = reason;
    return kind === 'zone' ? KMS_ZONE_CODE : KMS_FLOOR_CODE;
  }

  /** `$KMS`: solve (./kms.ts), answer `$KMS:c!`, move the servos together only when c is 0. */
  private kms(
    x: number,
    y: number,
    z: number,
    alpha: number | undefined,
    ms: number,
    t: number,
    out: string[],
  ) {
    this.counters.kms++;
    const k = solveKms(x, y, z, alpha, t, this.servos, this.arm, this.kmsSolver, (pwm) =>
      this.kmsKeepOutCode(pwm),
    );
    if (k.ikRefused) this.counters.rejected.ik++;
    out.push(encodeKmsResult(k.code));
    for (const m of k.moves) this.servos.moveTo(m.i, m.pwm, ms, t);
  }
}
