/**
 * The simulated arm's physical parameters, declared once. The numbers are chosen so that the
 * thresholds of PROTOCOL.md §5 can be shown in a demo: a servo that moves hard or stalls warms
 * past 60 °C and 75 °C, and three or more servos moving at full speed together pull the supply
 * below 6.5 V. Currents are per servo, in amperes; index i is the arm profile's i-th servo.
 */
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';
import type { KeepOutCheck, KmsSolver } from '@armtwin/controller';
import { unhandled } from '@armtwin/protocol';

/**
 * How the sim reports positions: `auto` each servo as its profile says (`units`: pulse widths
 * `#IIIPpppp!`, or §8 angle frames `#IIIA±ddd.dd!`), `angle` every servo in angle frames,
 * `pulse` every servo in pulse widths (clamped to 500–2500 µs). Declared once.
 */
export const REPORT_UNITS = ['auto', 'angle', 'pulse'] as const;
export type ReportUnits = (typeof REPORT_UNITS)[number];

/** Whether a servo is reported in angle frames: as asked, or (`auto`) as its profile says. */
export function reportAngle(report: ReportUnits, speaksAngleFrames: boolean): boolean {
  switch (report) {
    case 'auto':
      return speaksAngleFrames;
    case 'angle':
      return true;
    case 'pulse':
      return false;
    default:
      return unhandled(report);
  }
}

export interface SimModelOptions {
  /** The arm whose servos are simulated: ids, angle limits, polarity, top speed. */
  arm: ArmProfile;
  /** Ambient temperature, °C: where a servo at rest with no load settles. */
  ambientC: number;
  /** Supply voltage with no load, mV. */
  supplyMv: number;
  /** Internal resistance of the supply and its common wiring, Ω: the sag per ampere drawn. */
  supplyOhms: number;
  /** Resistance of each servo's own lead, Ω: a servo drawing more sees a little less. */
  servoLeadOhms: number;
  /** Current each servo draws holding its pose (the load: the shoulder holds the most). */
  holdAmps: readonly number[];
  /** Extra current of a servo moving at its top speed (scaled by the fraction of it). */
  moveAmps: number;
  /** Extra current of a stalled servo pushing against its jam. */
  stallAmps: number;
  /** Steady-state temperature rise per ampere drawn, °C/A. */
  degPerAmp: number;
  /** Thermal time constant of a servo, ms. */
  thermalTauMs: number;
  /** Temperature an overheat fault drives a servo to when none is given, °C. */
  overheatC: number;
  /** Thermal time constant while an overheat fault is on, ms (fast, for demos). */
  overheatTauMs: number;
  /**
   * Heat runs this many times faster than the clock (1 = real time): the thermal time
   * constants are divided by it, nothing else changes. For tests and demos that must not wait
   * minutes for a servo to warm (`armtwin sim --thermal-time-scale 4`).
   */
  thermalTimeScale: number;
  /** How positions are reported (see ReportUnits). */
  report: ReportUnits;
  /** Pulse widths at power-on, µs, by servo index (missing → 1500, the centre). */
  initialPwm: readonly number[];
  /**
   * Solves `$KMS` for an arm the §4 solver does not describe (a numeric profile, see
   * `profile.ts`): the status code and pulses by servo index (NaN = leave). Unset: `solveIk`.
   */
  kms?: KmsSolver;
  /**
   * Keep-out zones (the floor, `profile.ts`): the reason a move from the goal pose `from` to
   * `to` (pulses by servo index) is refused, or '' when it may run. Unset: no zones.
   */
  keepOut?: KeepOutCheck;
}

/** The keep-out check and the `$KMS` solver, in pulses by servo index (@armtwin/controller). */
export type { KeepOutCheck, KmsSolver } from '@armtwin/controller';

export const DEFAULT_SIM_MODEL_OPTIONS: SimModelOptions = {
  arm: DEMO_ARM,
  ambientC: 25,
  supplyMv: 7400,
  supplyOhms: 0.3,
  servoLeadOhms: 0.05,
  holdAmps: [0.05, 0.35, 0.2, 0.08, 0.03, 0.03],
  moveAmps: 0.9,
  stallAmps: 2.0,
  degPerAmp: 25,
  thermalTauMs: 20_000,
  overheatC: 85,
  overheatTauMs: 8_000,
  thermalTimeScale: 1,
  report: 'auto',
  initialPwm: [],
};
