/**
 * The status packet's error byte, which the two vendors use differently:
 * - Dynamixel 2.0: bit 7 is the alert (a hardware error; details in Hardware Error Status,
 *   address 70), bits 0–6 one error number about the instruction just received.
 * - Feetech: one flag per bit, all about the servo's health (the SDK's ERRBIT_*).
 */
import type { BusProtocol } from './protocols.ts';

/** Dynamixel error numbers 1…7, in order. */
export const DYNAMIXEL_ERRORS = [
  'result-fail',
  'instruction',
  'crc',
  'data-range',
  'data-length',
  'data-limit',
  'access',
] as const;
export type DynamixelError = (typeof DYNAMIXEL_ERRORS)[number];
export const DYNAMIXEL_ALERT_BIT = 0x80;

/** The Dynamixel error byte for an error number, with the alert bit when `alert`. */
export const dynamixelErrorByte = (error: DynamixelError | null, alert: boolean): number =>
  (error ? DYNAMIXEL_ERRORS.indexOf(error) + 1 : 0) | (alert ? DYNAMIXEL_ALERT_BIT : 0);

/** Bits of Dynamixel's Hardware Error Status (address 70). */
export const DYNAMIXEL_HARDWARE_ERRORS = {
  'input-voltage': 0x01,
  overheating: 0x04,
  'motor-encoder': 0x08,
  'electrical-shock': 0x10,
  overload: 0x20,
} as const;

/** Feetech error flags, bit by bit (feetech-servo-sdk's ERRBIT_VOLTAGE … ERRBIT_OVERLOAD). */
export const FEETECH_ERROR_BITS = {
  voltage: 0x01,
  'angle-sensor': 0x02,
  overheat: 0x04,
  overcurrent: 0x08,
  overload: 0x20,
} as const;
export type FeetechError = keyof typeof FEETECH_ERROR_BITS;

export type StatusProblem = DynamixelError | 'hardware-alert' | FeetechError | 'unknown';

/** What a status error byte says, as a list (empty when all is well). */
export function statusProblems(protocol: BusProtocol, errorByte: number): StatusProblem[] {
  switch (protocol) {
    case 'dynamixel': {
      const out: StatusProblem[] = [];
      const n = errorByte & 0x7f;
      if (n) out.push(DYNAMIXEL_ERRORS[n - 1] ?? 'unknown');
      if (errorByte & DYNAMIXEL_ALERT_BIT) out.push('hardware-alert');
      return out;
    }
    case 'feetech': {
      const out: StatusProblem[] = [];
      let known = 0;
      for (const [name, bit] of Object.entries(FEETECH_ERROR_BITS) as [FeetechError, number][]) {
        known |= bit;
        if (errorByte & bit) out.push(name);
      }
      if (errorByte & ~known & 0xff) out.push('unknown');
      return out;
    }
    default: {
      const never: never = protocol;
      throw new Error(`unknown protocol ${String(never)}`);
    }
  }
}
