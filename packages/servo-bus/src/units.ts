/**
 * Servo ticks ↔ joint degrees, per servo: where its zero is and which way it turns. Both
 * buses' models here count 4096 ticks per turn.
 */

export interface ServoCalibration {
  id: number;
  /** Ticks at which the joint reads 0°. */
  zeroTicks?: number;
  /** +1: degrees grow with ticks; −1: the servo is mounted the other way round. */
  direction?: 1 | -1;
  /** Position ticks per turn of the output shaft. */
  ticksPerTurn?: number;
}

export const DEFAULT_CALIBRATION = {
  zeroTicks: 2048,
  direction: 1 as 1 | -1,
  ticksPerTurn: 4096,
} as const;

export type Calibration = Required<ServoCalibration>;

/** The calibration with its defaults filled in. */
export const fullCalibration = (c: ServoCalibration): Calibration => ({
  ...DEFAULT_CALIBRATION,
  ...c,
});

/** Joint degrees at a servo position. */
export function ticksToDegrees(ticks: number, c: ServoCalibration): number {
  const { zeroTicks, direction, ticksPerTurn } = fullCalibration(c);
  return ((ticks - zeroTicks) * direction * 360) / ticksPerTurn;
}

/** Servo position (whole ticks, rounded) for joint degrees. */
export function degreesToTicks(degrees: number, c: ServoCalibration): number {
  const { zeroTicks, direction, ticksPerTurn } = fullCalibration(c);
  return zeroTicks + Math.round((degrees * direction * ticksPerTurn) / 360);
}

/** Degrees one tick stands for. */
export const degreesPerTick = (c: ServoCalibration): number =>
  360 / fullCalibration(c).ticksPerTurn;
