/**
 * The controller core: executes control frames the way the seed firmware did, for any driver
 * (./driver.ts). Limits and unknown servos are refused (./refusal.ts), then the keep-out rules
 * (the floor, zones, self-collision) for the move a frame or group starts; a `{…}` group runs
 * all together or not at all; `$KMS` goes through the solver and answers `$KMS:c!`; `#IIIPDST!`
 * holds a servo, `#255PDST!` every servo; the deadman holds a moving arm. Pure: time comes in
 * as an argument, replies go out as encoded frames appended to an array the caller owns.
 */
import {
  encodeControllerError,
  encodeGroup,
  encodeKmsResult,
  encodePing,
  KMS_FLOOR_CODE,
  KMS_LIMIT_CODE,
  KMS_ZONE_CODE,
  SERVO_ID_ALL,
  unhandled,
  type Frame,
  type Group,
} from '@armtwin/protocol';
import { keepOutKind } from '@armtwin/motion';
import type { ControllerDriver, Goal } from './driver.ts';
import type { Joint } from './joints.ts';
import { frameRefusal, pulseWithin, REFUSAL_KINDS, type RefusalKind } from './refusal.ts';
import type { KeepOutCheck, KmsSolver } from './rules.ts';

export const KMS_REPLY = 'kms: no IK for this profile';
export const DEADMAN_REPLY = 'deadman stop';

/** What the controller did with a command, counted by kind. */
export interface ControllerCounters {
  moves: number;
  groups: number;
  kms: number;
  stops: number;
  emergencyStops: number;
  /** Stops made because the operator left while the arm moved (each is an emergency stop too). */
  deadmanStops: number;
  rejected: Record<RefusalKind, number>;
}

export interface ControllerRules {
  /** `$KMS`; unset: `$KMS` is refused (`$ERR:kms: no IK for this profile!`). */
  kms?: KmsSolver;
  /** The floor, zones, self-collision; unset: none. */
  keepOut?: KeepOutCheck;
}

/** Frames that need the driver ready (they move or stop servos). */
const ACTS: ReadonlySet<Frame['type']> = new Set(['move', 'angleMove', 'stop', 'kms']);

export class ControllerCore {
  readonly counters: ControllerCounters = {
    moves: 0,
    groups: 0,
    kms: 0,
    stops: 0,
    emergencyStops: 0,
    deadmanStops: 0,
    rejected: Object.fromEntries(REFUSAL_KINDS.map((k) => [k, 0])) as Record<RefusalKind, number>,
  };
  /** Why the last move refused by a keep-out rule was refused ('' = none yet). */
  lastKeepOutRefusal = '';
  /** Goals of the frames applied so far in this command (a group's go out together). */
  private goals: Goal[] = [];
  /** Reads and pings of this command for a driver that relays them (`ControllerDriver.relay`). */
  private relayed: Frame[] = [];

  constructor(
    private joints_: readonly Joint[],
    readonly driver: ControllerDriver,
    private rules: ControllerRules = {},
  ) {}

  /** The joints, in the driver's order. */
  get joints(): readonly Joint[] {
    return this.joints_;
  }

  /** Puts a new calibration of the same servos and other rules in force (a profile file edited while running). */
  reconfigure(joints: readonly Joint[], rules: ControllerRules): void {
    if (joints.map((j) => j.id).join() !== this.joints_.map((j) => j.id).join())
      throw new RangeError('reconfigure: the same servos, in the same order');
    this.joints_ = joints;
    this.rules = rules;
  }

  /** Puts another keep-out check in force, the `$KMS` solver unchanged. */
  setKeepOut(keepOut: KeepOutCheck | undefined): void {
    this.rules = { ...this.rules, keepOut };
  }

  /** Executes one top-level frame received at t; appends reply frames to `out`. */
  execute(frame: Frame, t: number, out: string[]): void {
    const error = this.check(frame) || this.checkKeepOut([frame], t);
    if (error) {
      out.push(encodeControllerError(error));
      return;
    }
    const reads: string[] = [];
    this.apply(frame, t, reads, out);
    this.flush(t);
    this.relay(false, t, out);
    if (reads.length > 1) out.push(encodeGroup(reads));
    else if (reads.length === 1) out.push(reads[0]!);
  }

  /**
   * Executes a `{…}` group received at t: only when every frame in it decoded and passes its
   * checks, and then all together. Reads inside it are answered as one group.
   */
  executeGroup(group: Group, t: number, out: string[]): void {
    let error = group.invalid > 0 ? `group rejected: ${group.invalid} bad frame(s)` : '';
    for (const frame of group.frames) {
      if (error) break;
      const e = this.check(frame);
      if (e) error = `group rejected: ${e}`;
    }
    if (!error) {
      const e = this.checkKeepOut(group.frames, t);
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
    this.flush(t);
    this.relay(true, t, out);
    if (reads.length > 0) out.push(encodeGroup(reads));
  }

  /** Holds every servo where it is (`#255PDST!`): beats anything else. */
  emergencyStop(t: number): void {
    this.goals = [];
    this.counters.emergencyStops++;
    this.driver.hold(this.all(), t);
  }

  /**
   * The deadman: the operator left (let go, its last will, a lapsed lease). If the arm is on
   * its way (or `queued`: a command is still waiting in the driver's hands) every servo is held
   * where it is, as `#255PDST!` would, and `$ERR:deadman stop!` is appended to `out`. At rest
   * it does nothing. Returns whether it stopped the arm.
   */
  operatorLeft(t: number, out: string[], queued = false): boolean {
    if (!queued && !this.driver.moving(t)) return false;
    if (this.driver.unready()) return false;
    this.counters.deadmanStops++;
    this.emergencyStop(t);
    out.push(encodeControllerError(DEADMAN_REPLY));
    return true;
  }

  /** Counts a refusal by its kind; returns its reason. */
  refuse(kind: RefusalKind, reason: string): string {
    this.counters.rejected[kind]++;
    if (kind === 'floor' || kind === 'zone') this.lastKeepOutRefusal = reason;
    return reason;
  }

  private all(): number[] {
    return this.joints.map((_, i) => i);
  }

  /** The reason a frame cannot run, or '' when it can, counted by kind. */
  private check(frame: Frame): string {
    const r = frameRefusal(frame, this.joints);
    if (r) return this.refuse(r.kind, r.reason);
    const unready = ACTS.has(frame.type) ? this.driver.unready() : '';
    return unready ? this.refuse('not-ready', unready) : '';
  }

  /** The goals a (checked) move frame sets, by joint index. */
  private goalsOf(f: Frame): Goal[] {
    if (f.type !== 'move' && f.type !== 'angleMove') return [];
    const out: Goal[] = [];
    this.joints.forEach((j, i) => {
      if (f.id !== SERVO_ID_ALL && f.id !== j.id) return;
      out.push(
        f.type === 'move'
          ? { i, pwm: f.pwm, ms: f.ms }
          : { i, pwm: j.pwmOfAngle(f.deg), ms: f.ms, deg: f.deg },
      );
    });
    return out;
  }

  /** The keep-out reason for moving from the pose at t to these goals ('' = clear), counted. */
  private keepOutOf(goals: readonly Goal[], t: number): string {
    const check = this.rules.keepOut;
    if (!check || goals.length === 0) return '';
    const from = this.driver.pose(t);
    const to = [...from];
    for (const g of goals) to[g.i] = g.pwm;
    const reason = check(from, to);
    return reason ? this.refuse(keepOutKind(reason), reason) : '';
  }

  /** The keep-out rules for the move these (already checked) frames start. Changes nothing. */
  private checkKeepOut(frames: readonly Frame[], t: number): string {
    return this.keepOutOf(
      frames.flatMap((f) => this.goalsOf(f)),
      t,
    );
  }

  /** Hands the goals gathered so far to the driver, together. */
  private flush(t: number): void {
    if (this.goals.length === 0) return;
    const goals = this.goals;
    this.goals = [];
    this.driver.move(goals, t);
  }

  /** Hands the reads and pings gathered so far to a driver that relays them. */
  private relay(grouped: boolean, t: number, out: string[]): void {
    if (this.relayed.length === 0) return;
    const frames = this.relayed;
    this.relayed = [];
    const why = this.driver.relay?.(frames, grouped, t);
    if (why) out.push(encodeControllerError(this.refuse('not-ready', why)));
  }

  /** Runs a checked frame. Position and health reads go to `reads`, other replies to `out`. */
  private apply(frame: Frame, t: number, reads: string[], out: string[]): void {
    switch (frame.type) {
      case 'move':
      case 'angleMove':
        this.counters.moves++;
        this.goals.push(...this.goalsOf(frame));
        return;
      case 'stop':
        if (frame.id === SERVO_ID_ALL) return this.emergencyStop(t);
        this.flush(t);
        this.counters.stops++;
        return this.driver.hold([this.joints.findIndex((j) => j.id === frame.id)], t);
      case 'readPosition':
      case 'readHealth':
        if (this.driver.relay) return void this.relayed.push(frame);
        this.joints.forEach((j, i) => {
          if (frame.id !== SERVO_ID_ALL && frame.id !== j.id) return;
          const a = this.driver.read(frame.type === 'readPosition' ? 'position' : 'health', i, t);
          if ('frame' in a) reads.push(a.frame);
          else out.push(encodeControllerError(this.refuse('no-reading', a.refused)));
        });
        return;
      case 'kms':
        return this.kms(frame.x, frame.y, frame.z, frame.alpha, frame.ms, t, out);
      case 'ping':
        if (this.driver.relay) return void this.relayed.push(frame);
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
   * `$KMS:x,y,z[,a],t!`: solve, answer `$KMS:c!`, move every servo the solver gives a pulse
   * together only when c is 0 (8 past a joint's limit, 1 below the floor, 25 into a zone).
   */
  private kms(
    x: number,
    y: number,
    z: number,
    alpha: number | undefined,
    ms: number,
    t: number,
    out: string[],
  ): void {
    this.counters.kms++;
    const solver = this.rules.kms;
    if (!solver) {
      out.push(encodeControllerError(this.refuse('kms', KMS_REPLY)));
      return;
    }
    const now = this.driver.pose(t);
    const k = solver(x, y, z, alpha, now);
    let code = k.code;
    if (code !== 0) this.counters.rejected.ik++;
    const goals: Goal[] = [];
    if (code === 0)
      k.pwm.forEach((pwm, i) => {
        if (Number.isNaN(pwm) || i >= this.joints.length) return;
        if (pulseWithin(this.joints[i]!, pwm)) goals.push({ i, pwm, ms });
        else code = KMS_LIMIT_CODE;
      });
    if (code === 0) {
      const reason = this.keepOutOf(goals, t);
      if (reason) code = keepOutKind(reason) === 'zone' ? KMS_ZONE_CODE : KMS_FLOOR_CODE;
    }
    out.push(encodeKmsResult(code));
    if (code === 0) this.goals.push(...goals);
  }
}
