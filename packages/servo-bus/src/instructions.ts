/**
 * The instructions both buses share, as typed values, and their packets. The codes are the
 * same on both (Feetech copied them); what differs is the width of addresses and lengths in
 * the parameters (2 bytes on Dynamixel 2.0, 1 on Feetech) and that REBOOT is Dynamixel's only.
 */
import { le, readUnsigned } from './bytes.ts';
import { DIALECTS } from './dialect.ts';
import { BusError } from './errors.ts';
import type { InstructionPacket } from './packet.ts';
import { BROADCAST_ID, type BusProtocol } from './protocols.ts';

export const INSTRUCTION_OPS = [
  'ping',
  'read',
  'write',
  'reg-write',
  'action',
  'reboot',
  'sync-read',
  'sync-write',
] as const;
export type InstructionOp = (typeof INSTRUCTION_OPS)[number];

export const INSTRUCTION_CODES: Record<InstructionOp, number> = {
  ping: 0x01,
  read: 0x02,
  write: 0x03,
  'reg-write': 0x04,
  action: 0x05,
  reboot: 0x08,
  'sync-read': 0x82,
  'sync-write': 0x83,
};

/** Which instructions each bus has. */
export const SUPPORTED_OPS: Record<BusProtocol, readonly InstructionOp[]> = {
  dynamixel: INSTRUCTION_OPS,
  feetech: INSTRUCTION_OPS.filter((op) => op !== 'reboot'),
};

export interface SyncWriteEntry {
  id: number;
  /** exactly `length` bytes */
  data: Uint8Array;
}

export type Instruction =
  | { op: 'ping'; id: number }
  | { op: 'read'; id: number; address: number; length: number }
  | { op: 'write'; id: number; address: number; data: Uint8Array }
  | { op: 'reg-write'; id: number; address: number; data: Uint8Array }
  | { op: 'action'; id: number }
  | { op: 'reboot'; id: number }
  | { op: 'sync-read'; address: number; length: number; ids: number[] }
  | { op: 'sync-write'; address: number; length: number; writes: SyncWriteEntry[] };

const OP_BY_CODE = new Map(INSTRUCTION_OPS.map((op) => [INSTRUCTION_CODES[op], op]));

function field(protocol: BusProtocol, value: number, what: string): Uint8Array {
  const size = DIALECTS[protocol].fieldBytes;
  if (!Number.isInteger(value) || value < 0 || value >= 2 ** (8 * size))
    throw new BusError(
      'out-of-range',
      `${what} ${value} does not fit ${size} byte(s) on ${protocol}`,
    );
  return le(value, size);
}

function cat(...parts: (Uint8Array | number[])[]): Uint8Array {
  const out = new Uint8Array(parts.reduce((n, p) => n + p.length, 0));
  let at = 0;
  for (const p of parts) {
    out.set(p, at);
    at += p.length;
  }
  return out;
}

/** The packet of an instruction; throws `BusError` for values the bus cannot carry. */
export function instructionPacket(protocol: BusProtocol, ins: Instruction): InstructionPacket {
  if (!SUPPORTED_OPS[protocol].includes(ins.op))
    throw new BusError('unsupported', `${protocol} has no ${ins.op.toUpperCase()}`);
  const code = INSTRUCTION_CODES[ins.op];
  const packet = (id: number, params: Uint8Array): InstructionPacket => ({
    type: 'instruction',
    id,
    instruction: code,
    params,
  });
  switch (ins.op) {
    case 'ping':
    case 'action':
    case 'reboot':
      return packet(ins.id, new Uint8Array(0));
    case 'read':
      return packet(
        ins.id,
        cat(field(protocol, ins.address, 'address'), field(protocol, ins.length, 'length')),
      );
    case 'write':
    case 'reg-write':
      return packet(ins.id, cat(field(protocol, ins.address, 'address'), ins.data));
    case 'sync-read':
      return packet(
        BROADCAST_ID,
        cat(
          field(protocol, ins.address, 'address'),
          field(protocol, ins.length, 'length'),
          ins.ids,
        ),
      );
    case 'sync-write': {
      const parts: (Uint8Array | number[])[] = [
        field(protocol, ins.address, 'address'),
        field(protocol, ins.length, 'length'),
      ];
      for (const w of ins.writes) {
        if (w.data.length !== ins.length)
          throw new BusError(
            'out-of-range',
            `sync write to id ${w.id}: ${w.data.length} bytes, not ${ins.length}`,
          );
        parts.push([w.id], w.data);
      }
      return packet(BROADCAST_ID, cat(...parts));
    }
    default: {
      const never: never = ins;
      throw new Error(`unhandled instruction ${String(never)}`);
    }
  }
}

/** Bytes on the wire for an instruction. */
export const encodeInstruction = (protocol: BusProtocol, ins: Instruction): Uint8Array =>
  DIALECTS[protocol].encode(instructionPacket(protocol, ins));

export type DecodedInstruction =
  | { ok: true; instruction: Instruction }
  | { ok: false; reason: 'unknown-instruction' | 'bad-params'; message: string };

/** The instruction in a packet, or why the packet holds none this bus knows (never throws). */
export function decodeInstruction(
  protocol: BusProtocol,
  packet: InstructionPacket,
): DecodedInstruction {
  const op = OP_BY_CODE.get(packet.instruction);
  if (!op || !SUPPORTED_OPS[protocol].includes(op))
    return {
      ok: false,
      reason: 'unknown-instruction',
      message: `instruction 0x${packet.instruction.toString(16)}`,
    };
  const size = DIALECTS[protocol].fieldBytes;
  const p = packet.params;
  const bad = (message: string): DecodedInstruction => ({
    ok: false,
    reason: 'bad-params',
    message: `${op}: ${message}`,
  });
  const ok = (instruction: Instruction): DecodedInstruction => ({ ok: true, instruction });
  const id = packet.id;
  switch (op) {
    case 'ping':
    case 'action':
    case 'reboot':
      return ok({ op, id });
    case 'read':
      if (p.length !== 2 * size) return bad(`${p.length} parameter bytes, not ${2 * size}`);
      return ok({ op, id, address: readUnsigned(p, 0, size), length: readUnsigned(p, size, size) });
    case 'write':
    case 'reg-write':
      if (p.length <= size) return bad('no data');
      return ok({ op, id, address: readUnsigned(p, 0, size), data: p.slice(size) });
    case 'sync-read':
      if (p.length < 2 * size) return bad('no address and length');
      return ok({
        op,
        address: readUnsigned(p, 0, size),
        length: readUnsigned(p, size, size),
        ids: [...p.subarray(2 * size)],
      });
    case 'sync-write': {
      if (p.length < 2 * size) return bad('no address and length');
      const address = readUnsigned(p, 0, size);
      const length = readUnsigned(p, size, size);
      const rest = p.subarray(2 * size);
      if (length === 0 || rest.length % (length + 1) !== 0)
        return bad(`${rest.length} bytes are not whole (id + ${length}) entries`);
      const writes: SyncWriteEntry[] = [];
      for (let at = 0; at < rest.length; at += length + 1)
        writes.push({ id: rest[at]!, data: rest.slice(at + 1, at + 1 + length) });
      return ok({ op, address, length, writes });
    }
    default: {
      const never: never = op;
      throw new Error(`unhandled instruction ${String(never)}`);
    }
  }
}
