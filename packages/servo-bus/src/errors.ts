/**
 * Why a packet reader dropped input, declared once; every consumer counts them per kind.
 * - `junk`: bytes outside any packet (no header before them)
 * - `bad-checksum`: a whole packet whose CRC-16 (Dynamixel) or checksum (Feetech) is wrong
 * - `too-long`: a length field past the reader's `maxPacketLength`
 * - `malformed`: a header and checksum that hold, but a length or body no packet can have
 * - `truncated`: the stream ended (`flush()`) inside a packet
 */
export const PACKET_ERROR_KINDS = [
  'junk',
  'bad-checksum',
  'too-long',
  'malformed',
  'truncated',
] as const;
export type PacketErrorKind = (typeof PACKET_ERROR_KINDS)[number];

export interface PacketError {
  kind: PacketErrorKind;
  /** one-line human-readable reason */
  message: string;
  /** the dropped bytes (at most the reader's maxPacketLength of them) */
  bytes: Uint8Array;
}

/** A counter per error kind, all zero. */
export const emptyPacketErrorCounts = (): Record<PacketErrorKind, number> =>
  Object.fromEntries(PACKET_ERROR_KINDS.map((k) => [k, 0])) as Record<PacketErrorKind, number>;

/** Why an encoder or a bus client refused a call. Decoders and readers never throw. */
export const BUS_ERROR_KINDS = ['out-of-range', 'unsupported', 'busy', 'unknown-servo'] as const;
export type BusErrorKind = (typeof BUS_ERROR_KINDS)[number];

export class BusError extends Error {
  readonly kind: BusErrorKind;
  constructor(kind: BusErrorKind, message: string) {
    super(message);
    this.name = 'BusError';
    this.kind = kind;
  }
}
