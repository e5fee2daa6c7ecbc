/**
 * The simulated servos as a driver of the controller core (@armtwin/controller): the core
 * checks and executes control frames the way the firmware would, this carries out its goals on
 * the servo model and answers its reads. Pure: time comes in as an argument (epoch ms), replies
 * go out as encoded frame strings appended to an array the caller owns. The MQTT or serial side
 * lives elsewhere.
 */
import { speaksAngle, type ArmProfile } from '@armtwin/ik';
import {
  ControllerCore,
  id3,
  jointsFromArm,
  type ControllerCounters,
  type ControllerDriver,
  type Goal,
  type ReadAnswer,
} from '@armtwin/controller';
import {
  PWM_CENTRE,
  PWM_MAX,
  PWM_MIN,
  US_PER_DEG,
  encodeAngle,
  encodeHealth,
  encodePosition,
  type Frame,
  type Group,
} from '@armtwin/protocol';
import { DEFAULT_SIM_MODEL_OPTIONS, reportAngle, type SimModelOptions } from './options.ts';
import { analyticKms } from './kms.ts';
import { Servos } from './servos.ts';

/** What the controller did with a command, counted by kind (the core's counters). */
export type SimCounters = ControllerCounters;

export class SimModel implements ControllerDriver {
  readonly servos: Servos;
  readonly arm: ArmProfile;
  /** The controller: frames in, goals to these servos out. */
  readonly core: ControllerCore;
  /** Per servo index: 1 when its position is reported in §8 angle frames. */
  readonly reportsAngle: Uint8Array;
  /** Per servo index: mounting polarity, for servo angle ↔ the model's pulse-equivalent. */
  private readonly polarity: Float64Array;

  constructor(options: Partial<SimModelOptions> = {}, now = 0) {
    const o = { ...DEFAULT_SIM_MODEL_OPTIONS, ...options };
    this.arm = o.arm;
    this.servos = new Servos(o, now);
    this.core = new ControllerCore(jointsFromArm(o.arm), this, {
      kms: o.kms ?? analyticKms(o.arm),
      keepOut: o.keepOut,
    });
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

  /** What the controller did with commands, by kind. */
  get counters(): SimCounters {
    return this.core.counters;
  }

  /** Why the last move refused by a keep-out rule was refused ('' = none yet). */
  get lastKeepOutRefusal(): string {
    return this.core.lastKeepOutRefusal;
  }

  /** Executes one top-level frame received at t; appends reply frames to `out`. */
  execute(frame: Frame, t: number, out: string[]): void {
    this.advance(t);
    this.core.execute(frame, t, out);
  }

  /** Executes a `{…}` group received at t: all together or not at all (the core). */
  executeGroup(group: Group, t: number, out: string[]): void {
    this.advance(t);
    this.core.executeGroup(group, t, out);
  }

  /** Puts other keep-out rules in force (a profile file edited while running: zones-follow.ts). */
  setKeepOut(check: SimModelOptions['keepOut']): void {
    this.core.setKeepOut(check);
  }

  /** Stops every servo where it is now (`#255PDST!`). */
  emergencyStop(t: number): void {
    this.advance(t);
    this.core.emergencyStop(t);
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

  // The driver (@armtwin/controller): what the core asks of the servos.

  unready(): string {
    return '';
  }

  pose(t: number): number[] {
    return Array.from({ length: this.servos.count }, (_, i) => this.servos.pwmAt(i, t));
  }

  moving(t: number): boolean {
    this.advance(t);
    for (let i = 0; i < this.servos.count; i++) if (this.servos.isMoving(i, t)) return true;
    return false;
  }

  move(goals: readonly Goal[], t: number): void {
    this.advance(t);
    for (const g of goals) this.servos.moveTo(g.i, g.pwm, g.ms, t);
  }

  hold(indices: readonly number[], t: number): void {
    this.advance(t);
    for (const i of indices) this.servos.stop(i, t);
  }

  read(kind: 'position' | 'health', i: number, t: number): ReadAnswer {
    const s = this.servos;
    return {
      frame:
        kind === 'position'
          ? this.positionReport(i, t)
          : encodeHealth(s.ids[i]!, s.temp[i]!, s.mv[i]!),
    };
  }
}
