/**
 * The streaming packet reader both buses share: finds a header, waits for the length the
 * packet declares, checks its checksum, hands it on. What differs per vendor (header, length
 * field, checksum, body) comes in a `Framing`. No timers, no I/O.
 *
 * Resynchronisation: after a bad packet (checksum, length) the reader looks for the next header
 * one byte after the bad one's start, so a good packet that began inside it is still found; the
 * bytes it skips on the way belong to the error already reported and are not reported again.
 */
import { concatBytes } from './bytes.ts';
import type { PacketErrorKind } from './errors.ts';
import type { Packet, PacketReader, PacketReaderOptions } from './packet.ts';

export type HeaderMatch = 'header' | 'no' | 'partial';

export interface Framing {
  /** Whether a header starts at `i`; `partial` when the bytes from `i` to the end could begin one. */
  matchHeader(buf: Uint8Array, i: number): HeaderMatch;
  /** Bytes from a packet's start that tell its total length. */
  readonly prefixLength: number;
  /** Total wire length of the packet at `i` (needs `prefixLength` bytes), or why it cannot be one. */
  totalLength(buf: Uint8Array, i: number): number | string;
  /** Whether a whole packet's checksum holds. */
  verify(packet: Uint8Array): boolean;
  /** The packet in a whole, checked packet, or why it is not one. */
  decode(packet: Uint8Array, direction: 'instruction' | 'status'): Packet | string;
  /** Name of the check in messages: `CRC-16`, `checksum`. */
  readonly checkName: string;
}

export function createFramer(
  framing: Framing,
  options: PacketReaderOptions,
  defaultMaxPacketLength: number,
): PacketReader {
  const maxLen = options.maxPacketLength ?? defaultMaxPacketLength;
  const direction = options.direction ?? 'status';
  let pending: Uint8Array = new Uint8Array(0);
  let junk: number[] = [];
  let inJunk = false;
  let skipping = false; // the rest of a packet already reported: dropped silently

  function report(kind: PacketErrorKind, message: string, bytes: Uint8Array) {
    options.onError?.({ kind, message, bytes: bytes.slice(0, maxLen) });
  }

  function endJunk() {
    if (inJunk) report('junk', 'bytes outside any packet', Uint8Array.from(junk));
    inJunk = false;
    junk = [];
  }

  /** Reports a bad candidate at `i` and returns where to look next. */
  function reject(kind: PacketErrorKind, message: string, bytes: Uint8Array, i: number): number {
    endJunk();
    report(kind, message, bytes);
    skipping = true;
    return i + 1;
  }

  /**
   * Reads packets from `buf`; returns where the unread rest starts. At the end of the stream
   * (`final`) a packet cut short is reported and the bytes after its start are searched again,
   * so a good packet that a false header's length had swallowed is still found.
   */
  function scan(buf: Uint8Array, final: boolean): number {
    let i = 0;
    while (i < buf.length) {
      const match = framing.matchHeader(buf, i);
      if (match === 'no') {
        if (!skipping) {
          if (junk.length < maxLen) junk.push(buf[i]!);
          inJunk = true;
        }
        i++;
        continue;
      }
      if (match === 'partial') {
        if (!final) break;
        if (!skipping) {
          endJunk();
          report('truncated', 'stream ended inside a header', buf.subarray(i));
        }
        return buf.length;
      }
      if (buf.length - i < framing.prefixLength) {
        if (!final) break;
        i = reject('truncated', 'stream ended inside a packet', buf.subarray(i), i);
        continue;
      }
      skipping = false;
      const total = framing.totalLength(buf, i);
      if (typeof total === 'string') {
        i = reject('malformed', total, buf.subarray(i, i + framing.prefixLength), i);
        continue;
      }
      if (total > maxLen) {
        i = reject(
          'too-long',
          `packet of ${total} bytes, longer than ${maxLen}`,
          buf.subarray(i, i + framing.prefixLength),
          i,
        );
        continue;
      }
      if (buf.length - i < total) {
        if (!final) break;
        i = reject('truncated', 'stream ended inside a packet', buf.subarray(i), i);
        continue;
      }
      const bytes = buf.subarray(i, i + total);
      if (!framing.verify(bytes)) {
        i = reject('bad-checksum', `${framing.checkName} does not match`, bytes, i);
        continue;
      }
      const packet = framing.decode(bytes, direction);
      if (typeof packet === 'string') {
        i = reject('malformed', packet, bytes, i);
        continue;
      }
      endJunk();
      options.onPacket?.(packet);
      i += total;
    }
    return i;
  }

  function feed(chunk: Uint8Array) {
    const buf = concatBytes(pending, chunk);
    const i = scan(buf, false);
    pending = i < buf.length ? buf.slice(i) : new Uint8Array(0);
  }

  return {
    feed,
    flush() {
      const rest = pending;
      pending = new Uint8Array(0);
      scan(rest, true);
      endJunk();
      skipping = false;
    },
    reset() {
      pending = new Uint8Array(0);
      junk = [];
      inJunk = skipping = false;
    },
    get bufferedBytes() {
      return pending.length;
    },
  };
}
