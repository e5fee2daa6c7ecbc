/**
 * The Dynamixel X-series control table (XM430, XL430 and kin; ROBOTIS e-Manual, "Control
 * Table"), Protocol 2.0, and the models the emulator knows. Addresses 0–63 are EEPROM, written
 * only with torque off; the rest is RAM. Positions are 4096 ticks per turn, 2048 the middle.
 */
import type { Field, ServoModel } from '../control-table.ts';

const e = (address: number, size: 1 | 2 | 4, access: 'r' | 'rw' = 'rw', signed = false): Field => ({
  address,
  size,
  access,
  area: 'eeprom',
  ...(signed ? { sign: { kind: 'twos' as const } } : {}),
});
const r = (address: number, size: 1 | 2 | 4, access: 'r' | 'rw' = 'rw', signed = false): Field => ({
  ...e(address, size, access, signed),
  area: 'ram',
});

export const X_SERIES_TABLE = {
  modelNumber: e(0, 2, 'r'),
  modelInformation: e(2, 4, 'r'),
  firmwareVersion: e(6, 1, 'r'),
  id: e(7, 1),
  baudRate: e(8, 1),
  returnDelayTime: e(9, 1),
  driveMode: e(10, 1),
  operatingMode: e(11, 1),
  secondaryId: e(12, 1),
  protocolType: e(13, 1),
  homingOffset: e(20, 4, 'rw', true),
  movingThreshold: e(24, 4),
  temperatureLimit: e(31, 1),
  maxVoltageLimit: e(32, 2),
  minVoltageLimit: e(34, 2),
  pwmLimit: e(36, 2),
  currentLimit: e(38, 2),
  velocityLimit: e(44, 4),
  maxPositionLimit: e(48, 4),
  minPositionLimit: e(52, 4),
  shutdown: e(63, 1),
  torqueEnable: r(64, 1),
  led: r(65, 1),
  statusReturnLevel: r(68, 1),
  registeredInstruction: r(69, 1, 'r'),
  hardwareErrorStatus: r(70, 1, 'r'),
  velocityIGain: r(76, 2),
  velocityPGain: r(78, 2),
  positionDGain: r(80, 2),
  positionIGain: r(82, 2),
  positionPGain: r(84, 2),
  feedforward2ndGain: r(88, 2),
  feedforward1stGain: r(90, 2),
  busWatchdog: r(98, 1),
  goalPwm: r(100, 2, 'rw', true),
  goalCurrent: r(102, 2, 'rw', true),
  goalVelocity: r(104, 4, 'rw', true),
  profileAcceleration: r(108, 4),
  profileVelocity: r(112, 4),
  goalPosition: r(116, 4, 'rw', true),
  realtimeTick: r(120, 2, 'r'),
  moving: r(122, 1, 'r'),
  movingStatus: r(123, 1, 'r'),
  presentPwm: r(124, 2, 'r', true),
  presentCurrent: r(126, 2, 'r', true),
  presentVelocity: r(128, 4, 'r', true),
  presentPosition: r(132, 4, 'r', true),
  velocityTrajectory: r(136, 4, 'r', true),
  positionTrajectory: r(140, 4, 'r', true),
  presentInputVoltage: r(144, 2, 'r'),
  presentTemperature: r(146, 1, 'r'),
} as const satisfies Record<string, Field>;

export type XSeriesField = keyof typeof X_SERIES_TABLE;

/** Operating Mode (11) values the emulator moves in. */
export const DYNAMIXEL_OPERATING_MODES = { position: 3, extendedPosition: 4 } as const;
/** Goal Position range in extended position mode: ±256 turns. */
export const DYNAMIXEL_EXTENDED_POSITION_LIMIT = 1_048_575;
/** Unit of Profile Velocity and Velocity Limit: 0.229 rev/min. */
export const DYNAMIXEL_VELOCITY_UNIT_RPM = 0.229;
/** Unit of Present Input Voltage and the voltage limits: 0.1 V. */
export const DYNAMIXEL_VOLTAGE_UNIT_V = 0.1;
/** Baud Rate (8) values → bits per second. */
export const DYNAMIXEL_BAUD_RATES: Readonly<Record<number, number>> = {
  0: 9600,
  1: 57_600,
  2: 115_200,
  3: 1_000_000,
  4: 2_000_000,
  5: 3_000_000,
  6: 4_000_000,
  7: 4_500_000,
};

const ticksPerS = (velocityUnits: number) =>
  (velocityUnits * DYNAMIXEL_VELOCITY_UNIT_RPM * 4096) / 60;

const COMMON = {
  firmwareVersion: 46,
  id: 1,
  baudRate: 1,
  returnDelayTime: 250,
  operatingMode: DYNAMIXEL_OPERATING_MODES.position,
  secondaryId: 255,
  protocolType: 2,
  movingThreshold: 10,
  pwmLimit: 885,
  maxPositionLimit: 4095,
  minPositionLimit: 0,
  shutdown: 52,
  statusReturnLevel: 2,
  goalPwm: 885,
  goalPosition: 2048,
  presentPosition: 2048,
  presentTemperature: 25,
} as const;

/** XM430-W350 (OpenManipulator-X, many lab arms): 12 V. */
export const XM430_W350: ServoModel<XSeriesField> = {
  name: 'XM430-W350',
  protocol: 'dynamixel',
  modelNumber: 1020,
  ticksPerTurn: 4096,
  tableSize: 256,
  table: X_SERIES_TABLE,
  defaults: {
    ...COMMON,
    modelNumber: 1020,
    temperatureLimit: 80,
    maxVoltageLimit: 160,
    minVoltageLimit: 95,
    currentLimit: 1193,
    goalCurrent: 1193,
    velocityLimit: 167,
    velocityIGain: 1920,
    velocityPGain: 100,
    positionPGain: 800,
    presentInputVoltage: 120,
  },
  fullSpeedTicksPerS: ticksPerS(167),
};

/** XL430-W250 (Koch follower arms, TurtleBot3): 11.1 V. */
export const XL430_W250: ServoModel<XSeriesField> = {
  name: 'XL430-W250',
  protocol: 'dynamixel',
  modelNumber: 1060,
  ticksPerTurn: 4096,
  tableSize: 256,
  table: X_SERIES_TABLE,
  defaults: {
    ...COMMON,
    modelNumber: 1060,
    temperatureLimit: 72,
    maxVoltageLimit: 140,
    minVoltageLimit: 60,
    velocityLimit: 265,
    velocityIGain: 1000,
    velocityPGain: 100,
    positionDGain: 4000,
    positionPGain: 640,
    presentInputVoltage: 111,
  },
  fullSpeedTicksPerS: ticksPerS(265),
};

export const DYNAMIXEL_MODELS: readonly ServoModel<XSeriesField>[] = [XM430_W350, XL430_W250];
