/**
 * An LSC board (firmware with its own servo loop, `armtwin gateway --bus lsc`) as a driver of
 * the controller core (@armtwin/controller): the core checks every command first (limits, the
 * floor, zones, self-collision, `$KMS` through the profile's IK, the rate limit, the e-stop) and
 * this driver writes what passes to the firmware as frames it executes itself:
 *
 * - goals: one timed move (`#IIIPppppTtttt!`, or `#IIIA±ddd.ddTtttt!` when an angle was asked),
 *   several as one `{…}` group, which the firmware starts together. A `$KMS` solved here goes
 *   as pulses (rounded to whole µs, inside the limits).
 * - holds: `#255PDST!` for every servo (the e-stop, the deadman), else `#IIIPDST!` each.
 * - reads and pings: relayed as they came (a group stays a group); the firmware answers them.
 *
 * Positions are what the firmware reports (`#IIIPpppp!` / `#IIIA±ddd.dd!` on the serial line,
 * `report`); a servo not reported yet counts as at its last goal. The arm counts as moving
 * while a written move's time has not run out, or for `LSC_QUIET_MS` after a reported position
 * last changed. Pure: times come in as arguments.
 */
import type { ControllerDriver, Goal, Joint, ReadAnswer } from '@armtwin/controller';
import {
  EMERGENCY_STOP,
  encodeAngleMove,
  encodeFrame,
  encodeGroup,
  encodeMove,
  encodeStop,
  type Frame,
} from '@armtwin/protocol';
import { NOT_READY_REPLY } from './bus-driver.ts';

/** A reported position that changed less than this long ago means the arm still moves, ms. */
export const LSC_QUIET_MS = 250;

/** The serial line to the firmware. */
export interface LscLine {
  /** Writes frames to the firmware; false when the line is not open. */
  write(text: string): boolean;
}

export class LscDriver implements ControllerDriver {
  /** Reported positions, exact pulse-equivalents by joint index (NaN: none yet). */
  private at: number[];
  /** Last goal written, by joint index (NaN: none). */
  private goal: number[];
  private busyUntil = -Infinity;
  private changedAt = -Infinity;
  private open = false;

  constructor(
    private joints: readonly Joint[],
    private readonly line: LscLine,
  ) {
    this.at = joints.map(() => NaN);
    this.goal = joints.map(() => NaN);
  }

  /** The serial line opened or closed (positions are forgotten: the board may have restarted). */
  lineOpen(open: boolean): void {
    this.open = open;
    this.at = this.joints.map(() => NaN);
    this.goal = this.joints.map(() => NaN);
    this.busyUntil = -Infinity;
  }

  /** A new profile of the same servos, in the same order (new limits, zones). */
  setJoints(joints: readonly Joint[]): void {
    this.joints = joints;
  }

  /** A frame the firmware sent at t: its position reports are where the arm is. */
  report(frame: Frame, t: number): void {
    if (frame.type !== 'position' && frame.type !== 'angle') return;
    const i = this.joints.findIndex((j) => j.id === frame.id);
    if (i < 0) return;
    const pwm = frame.type === 'position' ? frame.pwm : this.joints[i]!.pwmOfAngle(frame.deg);
    if (!Number.isNaN(this.at[i]!) && Math.abs(pwm - this.at[i]!) > 1e-6) this.changedAt = t;
    this.at[i] = pwm;
  }

  unready(): string {
    return this.open ? '' : NOT_READY_REPLY;
  }

  pose(): number[] {
    return this.joints.map((_, i) => (Number.isNaN(this.at[i]!) ? this.goal[i]! : this.at[i]!));
  }

  moving(t: number): boolean {
    return t < this.busyUntil || t - this.changedAt < LSC_QUIET_MS;
  }

  move(goals: readonly Goal[], t: number): void {
    const frames = goals.map((g) => {
      const j = this.joints[g.i]!;
      this.goal[g.i] = g.pwm;
      if (g.deg !== undefined) return encodeAngleMove(j.id, g.deg, g.ms);
      const pwm = Math.min(Math.floor(j.maxPwm), Math.max(Math.ceil(j.minPwm), Math.round(g.pwm)));
      return encodeMove(j.id, pwm, g.ms);
    });
    if (frames.length === 0) return;
    this.busyUntil = Math.max(this.busyUntil, t + Math.max(...goals.map((g) => g.ms)));
    this.line.write(frames.length > 1 ? encodeGroup(frames) : frames[0]!);
  }

  hold(indices: readonly number[], t: number): void {
    const all = indices.length === this.joints.length;
    if (all) this.busyUntil = t;
    for (const i of indices) this.goal[i] = this.at[i]!;
    this.line.write(
      all ? EMERGENCY_STOP : indices.map((i) => encodeStop(this.joints[i]!.id)).join(''),
    );
  }

  /** Never asked: reads are relayed to the firmware, which answers them (`relay`). */
  read(): ReadAnswer {
    return { refused: 'the controller answers reads itself' };
  }

  relay(frames: readonly Frame[], grouped: boolean): string {
    const text = frames.map(encodeFrame);
    return this.line.write(grouped ? encodeGroup(text) : text.join('')) ? '' : NOT_READY_REPLY;
  }
}
