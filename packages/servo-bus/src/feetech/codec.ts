/**
 * Feetech SCS/STS packets (Feetech's "communication protocol" manual; the same layout as
 * Dynamixel Protocol 1.0):
 *
 *     FF FF | ID | LEN | INSTR or ERR | PARAM… | CHECKSUM
 *
 * LEN = parameters + 2; CHECKSUM = ~(ID + LEN + INSTR/ERR + PARAM…) & 0xFF. Instruction and
 * status packets look alike, so a reader is told which it reads (`direction`).
 */
import { BusError } from '../errors.ts';
import type { Framing, HeaderMatch } from '../framing.ts';
import { createFramer } from '../framing.ts';
import type { Packet, PacketReader, PacketReaderOptions } from '../packet.ts';

/** Longest packet the readers accept by default (the Feetech SDK's RXPACKET_MAX_LEN). */
export const FEETECH_MAX_PACKET_LENGTH = 250;
const PREFIX = 4;

/** ~sum of `bytes[start, end)`, low byte. */
export function feetechChecksum(bytes: Uint8Array, start = 2, end = bytes.length - 1): number {
  let sum = 0;
  for (let i = start; i < end; i++) sum += bytes[i]!;
  return ~sum & 0xff;
}

/** Bytes on the wire for a packet. */
export function encodeFeetechPacket(packet: Packet): Uint8Array {
  if (!Number.isInteger(packet.id) || packet.id < 0 || packet.id > 0xfe)
    throw new BusError('out-of-range', `Feetech id ${packet.id} is not 0…254`);
  const code = packet.type === 'status' ? packet.error : packet.instruction;
  if (!Number.isInteger(code) || code < 0 || code > 0xff)
    throw new BusError('out-of-range', `byte ${code} in a packet`);
  const length = packet.params.length + 2;
  if (length > 0xff)
    throw new BusError('out-of-range', `${packet.params.length} parameter bytes (at most 253)`);
  const out = new Uint8Array(PREFIX + length);
  out[0] = out[1] = 0xff;
  out[2] = packet.id;
  out[3] = length;
  out[4] = code;
  out.set(packet.params, 5);
  out[out.length - 1] = feetechChecksum(out);
  return out;
}

/** The packet in one whole wire packet, or why it is not one (never throws). */
export function decodeFeetechPacket(
  bytes: Uint8Array,
  direction: 'instruction' | 'status',
): Packet | string {
  if (bytes.length < PREFIX + 2) return 'shorter than any packet';
  if (bytes[0] !== 0xff || bytes[1] !== 0xff) return 'no FF FF header';
  if (bytes.length !== PREFIX + bytes[3]!)
    return `length field says ${bytes[3]}, packet has ${bytes.length - PREFIX}`;
  if (feetechChecksum(bytes) !== bytes[bytes.length - 1]) return 'checksum does not match';
  return bodyToPacket(bytes, direction);
}

function bodyToPacket(bytes: Uint8Array, direction: 'instruction' | 'status'): Packet | string {
  const id = bytes[2]!;
  if (id === 0xff) return 'id 255 is not an id';
  const params = bytes.slice(5, bytes.length - 1);
  return direction === 'status'
    ? { type: 'status', id, error: bytes[4]!, params }
    : { type: 'instruction', id, instruction: bytes[4]!, params };
}

const FRAMING: Framing = {
  matchHeader(buf, i): HeaderMatch {
    if (buf[i] !== 0xff) return 'no';
    if (i + 1 >= buf.length) return 'partial';
    if (buf[i + 1] !== 0xff) return 'no';
    if (i + 2 >= buf.length) return 'partial';
    // FF FF FF: the first FF is not the header's (id 255 does not exist); look again one on.
    return buf[i + 2] === 0xff ? 'no' : 'header';
  },
  prefixLength: PREFIX,
  totalLength(buf, i) {
    const length = buf[i + 3]!;
    return length < 2 ? `length field ${length} is below 2` : PREFIX + length;
  },
  verify: (packet) => feetechChecksum(packet) === packet[packet.length - 1],
  decode: bodyToPacket,
  checkName: 'checksum',
};

/** The streaming Feetech reader; `direction` says whether it reads instructions or replies. */
export function createFeetechReader(options: PacketReaderOptions = {}): PacketReader {
  return createFramer(FRAMING, options, FEETECH_MAX_PACKET_LENGTH);
}
