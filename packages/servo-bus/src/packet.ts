/**
 * The two kinds of packet on a servo bus, common to both vendors: the host's instruction and
 * the servo's status (reply), and the streaming reader's shape, after eventsource-parser's
 * `createParser({onEvent, onError})`: fed bytes, calls back, holds at most one packet.
 */
import type { PacketError } from './errors.ts';

/** Host → servo. `params` are the unstuffed parameter bytes. */
export interface InstructionPacket {
  type: 'instruction';
  id: number;
  instruction: number;
  params: Uint8Array;
}

/** Servo → host. `error` is the status error byte (its meaning differs per vendor). */
export interface StatusPacket {
  type: 'status';
  id: number;
  error: number;
  params: Uint8Array;
}

export type Packet = InstructionPacket | StatusPacket;

export interface PacketReaderOptions {
  /** A complete packet whose checksum holds. */
  onPacket?: (packet: Packet) => void;
  /** Dropped input, one call per dropped piece. */
  onError?: (error: PacketError) => void;
  /** Longest packet accepted on the wire, header to checksum; also the bound on the buffer. */
  maxPacketLength?: number;
  /**
   * What the stream carries where the bytes cannot tell (Feetech: an instruction and a status
   * packet look alike): `instruction` on the servo side, `status` on the host side. Dynamixel
   * status packets say so themselves (instruction 0x55), so its reader ignores this.
   */
  direction?: 'instruction' | 'status';
}

export interface PacketReader {
  /** Feeds any chunk: several packets, part of one, junk. Never throws. */
  feed(chunk: Uint8Array): void;
  /** End of stream: reports a pending partial packet or junk run. */
  flush(): void;
  /** Forgets everything pending without reporting it. */
  reset(): void;
  /** Bytes held for an incomplete packet; never more than maxPacketLength. */
  readonly bufferedBytes: number;
}
