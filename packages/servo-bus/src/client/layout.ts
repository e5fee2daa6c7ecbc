/**
 * Where the bus client finds what it reads and writes on each bus: the fields of the two
 * control tables it uses, and how a goal with a speed is laid out.
 */
import type { Field } from '../control-table.ts';
import {
  DYNAMIXEL_VELOCITY_UNIT_RPM,
  DYNAMIXEL_VOLTAGE_UNIT_V,
  X_SERIES_TABLE,
} from '../dynamixel/control-table.ts';
import { FEETECH_VOLTAGE_UNIT_V, STS_TABLE } from '../feetech/control-table.ts';
import type { BusProtocol } from '../protocols.ts';

export interface BusLayout {
  modelNumber: Field;
  torqueEnable: Field;
  goalPosition: Field;
  presentPosition: Field;
  presentVoltage: Field;
  presentTemperature: Field;
  voltageUnitV: number;
  /** The speed field written with the goal (one sync write), and its value for a speed. */
  goalSpeed: Field;
  speedUnits(degPerS: number, ticksPerTurn: number): number;
}

export const BUS_LAYOUTS: Record<BusProtocol, BusLayout> = {
  dynamixel: {
    modelNumber: X_SERIES_TABLE.modelNumber,
    torqueEnable: X_SERIES_TABLE.torqueEnable,
    goalPosition: X_SERIES_TABLE.goalPosition,
    presentPosition: X_SERIES_TABLE.presentPosition,
    presentVoltage: X_SERIES_TABLE.presentInputVoltage,
    presentTemperature: X_SERIES_TABLE.presentTemperature,
    voltageUnitV: DYNAMIXEL_VOLTAGE_UNIT_V,
    // Profile Velocity (112) sits just before Goal Position (116): one 8-byte sync write.
    goalSpeed: X_SERIES_TABLE.profileVelocity,
    speedUnits: (degPerS) => degPerS / 6 / DYNAMIXEL_VELOCITY_UNIT_RPM,
  },
  feetech: {
    modelNumber: STS_TABLE.modelNumber,
    torqueEnable: STS_TABLE.torqueEnable,
    goalPosition: STS_TABLE.goalPosition,
    presentPosition: STS_TABLE.presentPosition,
    presentVoltage: STS_TABLE.presentVoltage,
    presentTemperature: STS_TABLE.presentTemperature,
    voltageUnitV: FEETECH_VOLTAGE_UNIT_V,
    // Goal Position (42), Goal Time (44), Goal Speed (46): one 6-byte sync write.
    goalSpeed: STS_TABLE.goalSpeed,
    speedUnits: (degPerS, ticksPerTurn) => (degPerS * ticksPerTurn) / 360,
  },
};

/** The span of memory from the first field's start to the last one's end. */
export function span(...fields: Field[]): { address: number; length: number } {
  const address = Math.min(...fields.map((f) => f.address));
  const end = Math.max(...fields.map((f) => f.address + f.size));
  return { address, length: end - address };
}
