/**
 * The bus writes the gateway makes beyond what the bus client offers (pure, bytes out): goals
 * with a speed for each servo in one SYNC WRITE (so a group's moves start together and arrive
 * together), and the writes that switch a servo to multi-turn.
 */
import {
  BUS_LAYOUTS,
  degreesToTicks,
  DYNAMIXEL_OPERATING_MODES,
  encodeField,
  encodeInstruction,
  fieldRange,
  span,
  STS_TABLE,
  X_SERIES_TABLE,
  type BusProtocol,
  type ServoCalibration,
} from '@armtwin/servo-bus';
import type { BusGoal } from './bus-servos.ts';

/**
 * One SYNC WRITE of goal position and speed, each servo its own speed (no answer comes);
 * `calibration(id)`: the servo's zero and direction (`busCalibrations`).
 */
export function goalsWrite(
  protocol: BusProtocol,
  goals: readonly BusGoal[],
  calibration: (id: number) => ServoCalibration = (id) => ({ id }),
): Uint8Array {
  const layout = BUS_LAYOUTS[protocol];
  const g = layout.goalPosition;
  const s = layout.goalSpeed;
  const { address, length } = span(g, s);
  const writes = goals.map((goal) => {
    const data = new Uint8Array(length);
    data.set(
      encodeField(g, degreesToTicks(goal.degrees, calibration(goal.id))),
      g.address - address,
    );
    const units = Math.max(1, Math.round(layout.speedUnits(goal.speedDegPerS, 4096)));
    data.set(encodeField(s, Math.min(fieldRange(s).max, units)), s.address - address);
    return { id: goal.id, data };
  });
  return encodeInstruction(protocol, { op: 'sync-write', address, length, writes });
}

/** A WRITE the servo acknowledges: address and data. */
export interface ConfigWrite {
  address: number;
  data: Uint8Array;
}

/**
 * The writes (torque already off) that let a servo turn past one turn: Dynamixel's Operating
 * Mode 4 (extended position, ±256 turns); Feetech's angle limits both 0 (multi-turn position),
 * with the EEPROM lock opened and closed around them.
 */
export function multiTurnWrites(protocol: BusProtocol): ConfigWrite[] {
  if (protocol === 'dynamixel')
    return [
      {
        address: X_SERIES_TABLE.operatingMode.address,
        data: Uint8Array.of(DYNAMIXEL_OPERATING_MODES.extendedPosition),
      },
    ];
  return [
    { address: STS_TABLE.lock.address, data: Uint8Array.of(0) },
    { address: STS_TABLE.minPositionLimit.address, data: new Uint8Array(4) },
    { address: STS_TABLE.lock.address, data: Uint8Array.of(1) },
  ];
}
