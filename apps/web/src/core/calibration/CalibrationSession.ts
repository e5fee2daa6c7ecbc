/**
 * The calibration wizard's state for one bus servo (plain object, no React): the step, the
 * readings recorded, the wizard's slow jogs, and the ghost it draws (a `GhostSource`, sampled by
 * the 3D view's frame loop; nothing allocated per frame). Steps:
 *
 * 1. `zero`: the ghost shows the joint at its zero; the operator jogs the real joint there and
 *    records the reading.
 * 2. `direction`: the ghost leans the joint `DIRECTION_LEAN_DEG` positive; the operator moves
 *    the real joint the same way and records the reading (the sign of the change is the
 *    direction).
 * 3. `range`: the lowest and highest readings are recorded while the operator takes the joint
 *    to both ends (jogging, or by hand with torque off); the ghost shows the live joint as the
 *    new calibration reads it, over the live twin (old calibration) as the check.
 * 4. `review`: the result (`solveServoCalibration`), ghost as in 3, ready to save.
 *
 * Readings are the servo's §8 angle as reported (the store's `angle`), under the calibration
 * in force. Jogs are `#IIIA±ddd.ddTtttt!` at `CALIBRATION_JOG_DEG_PER_S`, within the limits in
 * force; an emergency stop forgets the wizard's target, so the next jog starts from where the
 * arm stopped.
 */
import {
  servoLimits,
  solveServoCalibration,
  type CalibrationResult,
  type Profile,
  type ProfileServo,
} from '@armtwin/robot';
import { encodeAngleMove, encodeGroup, MOVE_MS_MAX } from '@armtwin/protocol';
import type { GhostSource } from '../store/viewSources.ts';
import type { ArmStore } from '../store/ArmStore.ts';
import type { ArmCommands } from '../link/ArmCommands.ts';

export const CALIBRATION_STEPS = ['zero', 'direction', 'range', 'review'] as const;
export type CalibrationStep = (typeof CALIBRATION_STEPS)[number];

/** The wizard's jogs turn the servo this fast, degrees per second. */
export const CALIBRATION_JOG_DEG_PER_S = 15;
/** The shortest move time of a wizard jog, ms. */
const MIN_JOG_MS = 200;
/** How far the ghost leans the joint in the direction step, degrees. */
export const DIRECTION_LEAN_DEG = 30;
/** How often the travel is sampled while recording it, ms. */
const RECORD_EVERY_MS = 50;

const round2 = (v: number) => Math.round(v * 100) / 100 + 0;

/** What sends the wizard's frames: the arm link (`sendGroup` is false when nothing was sent). */
export type CalibrationLink = Pick<ArmCommands, 'sendGroup'>;

export class CalibrationSession implements GhostSource {
  /** The wizard is open: its ghost is drawn. */
  open = false;
  profile: Profile | null = null;
  /** Index of the servo being calibrated in `profile.servos` (−1 = none). */
  index = -1;
  step: CalibrationStep = 'zero';
  zero = NaN;
  positive = NaN;
  low = NaN;
  high = NaN;
  recording = false;
  /** The result was saved: the twin itself now shows the new calibration, the ghost goes. */
  saved = false;
  /** Where the last wizard jog sent the servo, servo degrees (NaN: from the live reading). */
  target = NaN;
  private timer: ReturnType<typeof setInterval> | undefined;

  constructor(private readonly store: ArmStore) {}

  get servo(): ProfileServo | undefined {
    return this.profile?.servos[this.index];
  }

  /** Starts over on servo `index` of `profile`. */
  begin(profile: Profile, index: number): void {
    this.stopRecording();
    this.profile = profile;
    this.index = index;
    this.step = 'zero';
    this.saved = false;
    this.zero = this.positive = this.low = this.high = this.target = NaN;
  }

  setOpen(open: boolean): void {
    this.open = open;
    if (!open) this.stopRecording();
  }

  /** The servo's latest reported angle, degrees (NaN = none yet). */
  reading(): number {
    return this.index < 0 ? NaN : (this.store.angle[this.index] ?? NaN);
  }

  /** Records the current reading for the step and moves on; false without a reading. */
  record(): boolean {
    const r = this.reading();
    if (!Number.isFinite(r)) return false;
    switch (this.step) {
      case 'zero':
        this.zero = r;
        this.step = 'direction';
        break;
      case 'direction':
        this.positive = r;
        this.step = 'range';
        this.startRecording(r);
        break;
      case 'range':
        this.track();
        this.stopRecording();
        this.step = 'review';
        break;
      case 'review':
        break;
      default: {
        const never: never = this.step;
        throw new Error(`unknown step ${String(never)}`);
      }
    }
    return true;
  }

  result(): CalibrationResult {
    const servo = this.servo;
    if (!servo) return { ok: false, error: 'no servo chosen' };
    return solveServoCalibration(servo, {
      id: servo.id,
      zero: this.zero,
      positive: this.positive,
      low: this.low,
      high: this.high,
    });
  }

  /**
   * A slow jog by `delta` degrees from the last wizard target (or the live reading): '' when
   * sent, else why not.
   */
  jog(link: CalibrationLink, delta: number): string {
    const servo = this.servo;
    if (!servo) return 'choose a joint first';
    const live = this.reading();
    const from = Number.isFinite(this.target) ? this.target : live;
    if (!Number.isFinite(from)) return 'no reading from this servo yet';
    const next = round2(from + delta);
    const { min, max } = servoLimits(servo);
    if (next < min || next > max)
      return `${next.toFixed(2)}° is outside the limits in force (${min}…${max}° of servo angle): turn torque off and move it by hand`;
    const distance = Number.isFinite(live) ? Math.abs(next - live) : Math.abs(delta);
    const ms = Math.min(
      MOVE_MS_MAX,
      Math.max(MIN_JOG_MS, Math.ceil((distance / CALIBRATION_JOG_DEG_PER_S) * 1000)),
    );
    if (!link.sendGroup(encodeGroup([encodeAngleMove(servo.id, next, ms)])))
      return 'not sent: not connected, or this log-in may not move the arm';
    this.target = next;
    return '';
  }

  /** The result is in the profile now: the ghost goes (the twin shows the new calibration). */
  markSaved(): void {
    this.saved = true;
  }

  /** The emergency stop was pressed: the next jog starts from where the arm stopped. */
  stopped(): void {
    this.target = NaN;
  }

  /** The joint as the calibration being made reads `reading` (NaN before zero and direction). */
  calibratedJoint(reading: number): number {
    const moved = this.positive - this.zero;
    if (!(Math.abs(moved) > 0)) return NaN;
    return Math.sign(moved) * (reading - this.zero);
  }

  sample(_now: number, out: Float64Array): boolean {
    const servo = this.servo;
    if (!this.open || !servo || this.saved) return false;
    const rendered = this.store.rendered;
    for (let i = 0; i < out.length; i++) out[i] = rendered[i] ?? NaN;
    const joint =
      this.step === 'zero'
        ? 0
        : this.step === 'direction'
          ? DIRECTION_LEAN_DEG
          : this.calibratedJoint(this.reading());
    if (!Number.isFinite(joint)) return false;
    // in the terms of the calibration in force, which the twin is drawn by
    out[this.index] = joint - servo.offset;
    return true;
  }

  private startRecording(r: number): void {
    this.low = this.high = r;
    this.recording = true;
    clearInterval(this.timer);
    this.timer = setInterval(() => this.track(), RECORD_EVERY_MS);
  }

  private track(): void {
    const r = this.reading();
    if (!Number.isFinite(r)) return;
    this.low = Math.min(this.low, r);
    this.high = Math.max(this.high, r);
  }

  private stopRecording(): void {
    clearInterval(this.timer);
    this.timer = undefined;
    this.recording = false;
  }
}
