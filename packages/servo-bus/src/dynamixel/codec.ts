/**
 * Dynamixel Protocol 2.0 packets (ROBOTIS e-Manual, "Protocol 2.0"):
 *
 *     FF FF FD 00 | ID | LEN_L LEN_H | INSTR | [ERR] | PARAM… | CRC_L CRC_H
 *
 * LEN counts what follows it (instruction, error, parameters, CRC) after stuffing. A status
 * packet is instruction 0x55 followed by the error byte. The CRC-16 covers the whole packet.
 */
import { BusError } from '../errors.ts';
import type { Framing, HeaderMatch } from '../framing.ts';
import { createFramer } from '../framing.ts';
import type { Packet, PacketReader, PacketReaderOptions } from '../packet.ts';
import { crc16 } from './crc.ts';
import { stuff, unstuff } from './stuffing.ts';

export const DYNAMIXEL_HEADER = [0xff, 0xff, 0xfd, 0x00] as const;
/** The instruction byte of a status packet. */
export const DYNAMIXEL_STATUS_INSTRUCTION = 0x55;
/** Header, id and length: the bytes before the body. */
const PREFIX = 7;
/** Longest packet on the wire the readers accept by default (the ROBOTIS SDK's RXPACKET_MAX_LEN). */
export const DYNAMIXEL_MAX_PACKET_LENGTH = 1024;

/** Bytes on the wire for a packet: header, stuffing, length and CRC included. */
export function encodeDynamixelPacket(packet: Packet): Uint8Array {
  if (!Number.isInteger(packet.id) || packet.id < 0 || packet.id > 0xfe || packet.id === 0xfd)
    throw new BusError('out-of-range', `Dynamixel id ${packet.id} is not 0…252 or 254`);
  const head =
    packet.type === 'status' ? [DYNAMIXEL_STATUS_INSTRUCTION, packet.error] : [packet.instruction];
  for (const b of head)
    if (!Number.isInteger(b) || b < 0 || b > 0xff)
      throw new BusError('out-of-range', `byte ${b} in a packet`);
  const raw = new Uint8Array(head.length + packet.params.length);
  raw.set(head, 0);
  raw.set(packet.params, head.length);
  const body = stuff(raw);
  const length = body.length + 2;
  if (length > 0xffff) throw new BusError('out-of-range', `packet body of ${body.length} bytes`);
  const out = new Uint8Array(PREFIX + length);
  out.set(DYNAMIXEL_HEADER, 0);
  out[4] = packet.id;
  out[5] = length & 0xff;
  out[6] = length >> 8;
  out.set(body, PREFIX);
  const crc = crc16(out, 0, out.length - 2);
  out[out.length - 2] = crc & 0xff;
  out[out.length - 1] = crc >> 8;
  return out;
}

/** The packet in one whole wire packet, or why it is not one (never throws). */
export function decodeDynamixelPacket(bytes: Uint8Array): Packet | string {
  if (bytes.length < PREFIX + 3) return 'shorter than any packet';
  for (let k = 0; k < 4; k++) if (bytes[k] !== DYNAMIXEL_HEADER[k]) return 'no FF FF FD 00 header';
  const length = bytes[5]! | (bytes[6]! << 8);
  if (bytes.length !== PREFIX + length)
    return `length field says ${length}, packet has ${bytes.length - PREFIX}`;
  const crc = bytes[bytes.length - 2]! | (bytes[bytes.length - 1]! << 8);
  if (crc16(bytes, 0, bytes.length - 2) !== crc) return 'CRC-16 does not match';
  return bodyToPacket(bytes);
}

function bodyToPacket(bytes: Uint8Array): Packet | string {
  const id = bytes[4]!;
  if (id === 0xfd || id === 0xff) return `id ${id} is reserved`;
  const body = unstuff(bytes.subarray(PREFIX, bytes.length - 2));
  const instruction = body[0]!;
  if (instruction !== DYNAMIXEL_STATUS_INSTRUCTION)
    return { type: 'instruction', id, instruction, params: body.slice(1) };
  if (body.length < 2) return 'status packet without an error byte';
  return { type: 'status', id, error: body[1]!, params: body.slice(2) };
}

const FRAMING: Framing = {
  matchHeader(buf, i): HeaderMatch {
    for (let k = 0; k < 4; k++) {
      if (i + k >= buf.length) return 'partial';
      if (buf[i + k] !== DYNAMIXEL_HEADER[k]) return 'no';
    }
    return 'header';
  },
  prefixLength: PREFIX,
  totalLength(buf, i) {
    const length = buf[i + 5]! | (buf[i + 6]! << 8);
    return length < 3 ? `length field ${length} is below 3` : PREFIX + length;
  },
  verify(packet) {
    const crc = packet[packet.length - 2]! | (packet[packet.length - 1]! << 8);
    return crc16(packet, 0, packet.length - 2) === crc;
  },
  decode: (packet) => bodyToPacket(packet),
  checkName: 'CRC-16',
};

/** The streaming Dynamixel 2.0 reader: instruction and status packets, told apart by 0x55. */
export function createDynamixelReader(options: PacketReaderOptions = {}): PacketReader {
  return createFramer(FRAMING, options, DYNAMIXEL_MAX_PACKET_LENGTH);
}
