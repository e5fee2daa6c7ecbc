/** A host for tests: sends instructions to an emulated bus and reads its answers back. */
import {
  createPacketReader,
  encodeInstruction,
  type EmulatedBus,
  type Instruction,
  type StatusPacket,
} from '../src/index.ts';

export function send(bus: EmulatedBus, ins: Instruction | Uint8Array): StatusPacket[] {
  const bytes = ins instanceof Uint8Array ? ins : encodeInstruction(bus.protocol, ins);
  const replies: StatusPacket[] = [];
  const reader = createPacketReader(bus.protocol, {
    direction: 'status',
    onPacket: (p) => (p.type === 'status' ? replies.push(p) : undefined),
    onError: (e) => {
      throw new Error(`bad reply: ${e.kind}`);
    },
  });
  reader.feed(bus.feed(bytes));
  reader.flush();
  return replies;
}

/** The one reply to an instruction. */
export function reply(bus: EmulatedBus, ins: Instruction | Uint8Array): StatusPacket {
  const replies = send(bus, ins);
  if (replies.length !== 1) throw new Error(`expected one reply, got ${replies.length}`);
  return replies[0]!;
}

export const u8 = (...bytes: number[]) => Uint8Array.from(bytes);
export const le32 = (v: number) =>
  u8(v & 0xff, (v >> 8) & 0xff, (v >> 16) & 0xff, (v >>> 24) & 0xff);
export const le16 = (v: number) => u8(v & 0xff, (v >> 8) & 0xff);
