/**
 * Control tables (the servo's memory map) as data: each field's address, size, access, area
 * and how it stores negative numbers, plus the model descriptions built on them. Used by the
 * emulated servos to hold their memory and by the bus client to encode and decode values.
 */
import {
  fromSignMagnitude,
  readUnsigned,
  signMagnitudeMax,
  toSigned,
  toSignMagnitude,
  writeUnsigned,
} from './bytes.ts';
import { BusError } from './errors.ts';
import type { BusProtocol } from './protocols.ts';

export type FieldSign = { kind: 'twos' } | { kind: 'magnitude'; bit: number };

export interface Field {
  address: number;
  size: 1 | 2 | 4;
  /** `r`: read-only; `rw`: read and write. */
  access: 'r' | 'rw';
  /** EEPROM keeps its value over power cycles (Dynamixel refuses to write it with torque on). */
  area: 'eeprom' | 'ram';
  /** Absent: unsigned. `twos`: two's complement (Dynamixel). `magnitude`: Feetech's sign bit. */
  sign?: FieldSign;
}

export interface ServoModel<F extends string = string> {
  /** Vendor's name, e.g. `XM430-W350`, `STS3215`. */
  name: string;
  protocol: BusProtocol;
  /** What the servo reports as its model number. */
  modelNumber: number;
  /** Position ticks per turn of the output shaft. */
  ticksPerTurn: number;
  /** Bytes of memory the servo answers for; reads past it fail. */
  tableSize: number;
  table: Readonly<Record<F, Field>>;
  /** Power-on values; fields not listed start at 0. */
  defaults: Readonly<Partial<Record<F, number>>>;
  /**
   * Speed when the goal speed is 0 ("as fast as it can"), ticks/s. The emulated Dynamixel
   * servos take it from their Velocity Limit field instead, which defaults to the same.
   */
  fullSpeedTicksPerS: number;
}

/** Smallest and largest value a field can hold. */
export function fieldRange(field: Field): { min: number; max: number } {
  const bits = 8 * field.size;
  if (!field.sign) return { min: 0, max: 2 ** bits - 1 };
  if (field.sign.kind === 'twos') return { min: -(2 ** (bits - 1)), max: 2 ** (bits - 1) - 1 };
  const max = signMagnitudeMax(field.sign.bit);
  return { min: -max, max };
}

/** The value of a field from its raw bytes at `offset`. */
export function decodeField(field: Field, bytes: Uint8Array, offset = 0): number {
  const raw = readUnsigned(bytes, offset, field.size);
  if (!field.sign) return raw;
  return field.sign.kind === 'twos'
    ? toSigned(raw, field.size)
    : fromSignMagnitude(raw, field.sign.bit);
}

/** The raw bytes of a value; throws `BusError('out-of-range')` when the field cannot hold it. */
export function encodeField(
  field: Field,
  value: number,
  name = `field ${field.address}`,
): Uint8Array {
  const { min, max } = fieldRange(field);
  if (!Number.isInteger(value) || value < min || value > max)
    throw new BusError('out-of-range', `${name}: ${value} is not an integer in ${min}…${max}`);
  const out = new Uint8Array(field.size);
  writeUnsigned(
    out,
    0,
    field.size,
    field.sign?.kind === 'magnitude' ? toSignMagnitude(value, field.sign.bit) : value,
  );
  return out;
}

/** The field holding `address`, if any, by its name. */
export function fieldAt<F extends string>(
  table: Readonly<Record<F, Field>>,
  address: number,
): F | undefined {
  for (const name of Object.keys(table) as F[]) {
    const f = table[name];
    if (address >= f.address && address < f.address + f.size) return name;
  }
  return undefined;
}

/** Memory laid out as the model's table with its defaults. */
export function initialMemory<F extends string>(model: ServoModel<F>): Uint8Array {
  const mem = new Uint8Array(model.tableSize);
  for (const name of Object.keys(model.defaults) as F[]) {
    const value = model.defaults[name];
    if (value !== undefined)
      mem.set(encodeField(model.table[name], value, name), model.table[name].address);
  }
  return mem;
}
