/** Test-vector JSON ↔ the package's types: byte fields are hex strings in the files. */
import { fromHex, type Instruction, type Packet, type PacketError } from '../src/index.ts';

export interface JsonPacket {
  type: 'instruction' | 'status';
  id: number;
  instruction?: number;
  error?: number;
  params: string;
}

export interface PacketVector {
  name: string;
  source: string;
  hex: string;
  direction?: 'instruction' | 'status';
  packet: JsonPacket;
  instruction?: Record<string, unknown>;
  unknown?: boolean;
}

export interface ReaderVector {
  name: string;
  direction?: 'instruction' | 'status';
  chunks: string[];
  packets: JsonPacket[];
  errors: string[];
}

export function toPacket(p: JsonPacket): Packet {
  return p.type === 'status'
    ? { type: 'status', id: p.id, error: p.error ?? 0, params: fromHex(p.params) }
    : { type: 'instruction', id: p.id, instruction: p.instruction ?? 0, params: fromHex(p.params) };
}

/** An instruction from JSON: `data` fields are hex. */
export function toInstruction(j: Record<string, unknown>): Instruction {
  const out: Record<string, unknown> = { ...j };
  if (typeof j.data === 'string') out.data = fromHex(j.data);
  if (Array.isArray(j.writes))
    out.writes = (j.writes as { id: number; data: string }[]).map((w) => ({
      id: w.id,
      data: fromHex(w.data),
    }));
  return out as unknown as Instruction;
}

/** Runs a reader over chunks and returns what it reported. */
export function collect(
  make: (o: { onPacket: (p: Packet) => void; onError: (e: PacketError) => void }) => {
    feed(c: Uint8Array): void;
    flush(): void;
  },
  chunks: Uint8Array[],
): { packets: Packet[]; errors: string[] } {
  const packets: Packet[] = [];
  const errors: string[] = [];
  const reader = make({ onPacket: (p) => packets.push(p), onError: (e) => errors.push(e.kind) });
  for (const c of chunks) reader.feed(c);
  reader.flush();
  return { packets, errors };
}
