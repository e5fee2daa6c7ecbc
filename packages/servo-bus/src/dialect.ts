/**
 * What differs between the two buses at the packet level, in one object per protocol, so that
 * the instruction layer, the emulated bus and the bus client are written once.
 */
import {
  createDynamixelReader,
  DYNAMIXEL_MAX_PACKET_LENGTH,
  encodeDynamixelPacket,
} from './dynamixel/codec.ts';
import {
  createFeetechReader,
  encodeFeetechPacket,
  FEETECH_MAX_PACKET_LENGTH,
} from './feetech/codec.ts';
import type { Packet, PacketReader, PacketReaderOptions } from './packet.ts';
import type { BusProtocol } from './protocols.ts';

export interface Dialect {
  readonly protocol: BusProtocol;
  /** Bytes of an address or a data length in READ, WRITE and SYNC parameters. */
  readonly fieldBytes: 1 | 2;
  /** The readers' default bound. */
  readonly maxPacketLength: number;
  encode(packet: Packet): Uint8Array;
  createReader(options: PacketReaderOptions): PacketReader;
}

export const DIALECTS: Record<BusProtocol, Dialect> = {
  dynamixel: {
    protocol: 'dynamixel',
    fieldBytes: 2,
    maxPacketLength: DYNAMIXEL_MAX_PACKET_LENGTH,
    encode: encodeDynamixelPacket,
    createReader: createDynamixelReader,
  },
  feetech: {
    protocol: 'feetech',
    fieldBytes: 1,
    maxPacketLength: FEETECH_MAX_PACKET_LENGTH,
    encode: encodeFeetechPacket,
    createReader: createFeetechReader,
  },
};

/** Bytes on the wire for a packet of either bus. */
export const encodePacket = (protocol: BusProtocol, packet: Packet): Uint8Array =>
  DIALECTS[protocol].encode(packet);

/** A streaming reader for either bus. */
export const createPacketReader = (
  protocol: BusProtocol,
  options: PacketReaderOptions = {},
): PacketReader => DIALECTS[protocol].createReader(options);
