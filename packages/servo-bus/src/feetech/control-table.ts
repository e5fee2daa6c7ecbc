/**
 * The Feetech STS memory table (STS3215 of the SO-100/SO-101 arms; Feetech's STS/SMS manual,
 * as LeRobot's `STS_SMS_SERIES_CONTROL_TABLE` lists it). Words are little-endian (STS/SMS; the
 * older SCS series is big-endian and not covered). Negative values use a sign bit (bit 15 for
 * positions and speeds, 10 for load, 11 for the homing offset), not two's complement.
 * Positions are 4096 steps per turn, 2048 the middle.
 */
import type { Field, ServoModel } from '../control-table.ts';

const e = (address: number, size: 1 | 2, access: 'r' | 'rw' = 'rw', signBit?: number): Field => ({
  address,
  size,
  access,
  area: 'eeprom',
  ...(signBit === undefined ? {} : { sign: { kind: 'magnitude' as const, bit: signBit } }),
});
const r = (address: number, size: 1 | 2, access: 'r' | 'rw' = 'rw', signBit?: number): Field => ({
  ...e(address, size, access, signBit),
  area: 'ram',
});

export const STS_TABLE = {
  firmwareMajorVersion: e(0, 1, 'r'),
  firmwareMinorVersion: e(1, 1, 'r'),
  modelNumber: e(3, 2, 'r'),
  id: e(5, 1),
  baudRate: e(6, 1),
  returnDelayTime: e(7, 1),
  responseStatusLevel: e(8, 1),
  minPositionLimit: e(9, 2),
  maxPositionLimit: e(11, 2),
  maxTemperatureLimit: e(13, 1),
  maxVoltageLimit: e(14, 1),
  minVoltageLimit: e(15, 1),
  maxTorqueLimit: e(16, 2),
  phase: e(18, 1),
  unloadingCondition: e(19, 1),
  ledAlarmCondition: e(20, 1),
  pCoefficient: e(21, 1),
  dCoefficient: e(22, 1),
  iCoefficient: e(23, 1),
  minimumStartupForce: e(24, 2),
  cwDeadZone: e(26, 1),
  ccwDeadZone: e(27, 1),
  protectionCurrent: e(28, 2),
  angularResolution: e(30, 1),
  homingOffset: e(31, 2, 'rw', 11),
  operatingMode: e(33, 1),
  protectiveTorque: e(34, 1),
  protectionTime: e(35, 1),
  overloadTorque: e(36, 1),
  torqueEnable: r(40, 1),
  acceleration: r(41, 1),
  goalPosition: r(42, 2, 'rw', 15),
  goalTime: r(44, 2),
  goalSpeed: r(46, 2, 'rw', 15),
  torqueLimit: r(48, 2),
  lock: r(55, 1),
  presentPosition: r(56, 2, 'r', 15),
  presentSpeed: r(58, 2, 'r', 15),
  presentLoad: r(60, 2, 'r', 10),
  presentVoltage: r(62, 1, 'r'),
  presentTemperature: r(63, 1, 'r'),
  status: r(65, 1, 'r'),
  moving: r(66, 1, 'r'),
  presentCurrent: r(69, 2, 'r'),
} as const satisfies Record<string, Field>;

export type StsField = keyof typeof STS_TABLE;

/** Unit of Present Voltage and the voltage limits: 0.1 V. */
export const FEETECH_VOLTAGE_UNIT_V = 0.1;
/** Torque Enable value that makes the present position read 2048 (sets the homing offset). */
export const FEETECH_TORQUE_CALIBRATE_MIDDLE = 128;
/** Baud Rate (6) values → bits per second. */
export const FEETECH_BAUD_RATES: Readonly<Record<number, number>> = {
  0: 1_000_000,
  1: 500_000,
  2: 250_000,
  3: 128_000,
  4: 115_200,
  5: 57_600,
  6: 38_400,
  7: 19_200,
};

/** STS3215 (SO-100/SO-101 arms). Goal Speed is in steps/s; 0 means full speed. */
export const STS3215: ServoModel<StsField> = {
  name: 'STS3215',
  protocol: 'feetech',
  modelNumber: 777,
  ticksPerTurn: 4096,
  tableSize: 128,
  table: STS_TABLE,
  defaults: {
    firmwareMajorVersion: 3,
    firmwareMinorVersion: 10,
    modelNumber: 777,
    id: 1,
    baudRate: 0,
    returnDelayTime: 0,
    responseStatusLevel: 1,
    minPositionLimit: 0,
    maxPositionLimit: 4095,
    maxTemperatureLimit: 70,
    maxVoltageLimit: 140,
    minVoltageLimit: 40,
    maxTorqueLimit: 1000,
    unloadingCondition: 44,
    ledAlarmCondition: 47,
    pCoefficient: 32,
    dCoefficient: 32,
    torqueLimit: 1000,
    lock: 1,
    goalPosition: 2048,
    presentPosition: 2048,
    presentVoltage: 74,
    presentTemperature: 25,
  },
  // The emulator's "full speed": about 264 °/s.
  fullSpeedTicksPerS: 3000,
};

export const FEETECH_MODELS: readonly ServoModel<StsField>[] = [STS3215];
