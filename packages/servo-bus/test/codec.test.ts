import { describe, expect, it } from 'vitest';
import {
  createDynamixelReader,
  createFeetechReader,
  decodeDynamixelPacket,
  decodeFeetechPacket,
  decodeInstruction,
  encodeDynamixelPacket,
  encodeFeetechPacket,
  encodeInstruction,
  fromHex,
  toHex,
  type BusProtocol,
  type PacketReaderOptions,
} from '../src/index.ts';
import dynamixelPackets from './vectors/dynamixel-packets.json' with { type: 'json' };
import dynamixelReader from './vectors/dynamixel-reader.json' with { type: 'json' };
import feetechPackets from './vectors/feetech-packets.json' with { type: 'json' };
import feetechReader from './vectors/feetech-reader.json' with { type: 'json' };
import {
  collect,
  toInstruction,
  toPacket,
  type PacketVector,
  type ReaderVector,
} from './vectors.ts';

const CODECS = {
  dynamixel: {
    packets: dynamixelPackets as PacketVector[],
    reader: dynamixelReader as ReaderVector[],
    encode: encodeDynamixelPacket,
    decode: (b: Uint8Array) => decodeDynamixelPacket(b),
    createReader: (o: PacketReaderOptions) => createDynamixelReader(o),
  },
  feetech: {
    packets: feetechPackets as PacketVector[],
    reader: feetechReader as ReaderVector[],
    encode: encodeFeetechPacket,
    decode: (b: Uint8Array, d: 'instruction' | 'status') => decodeFeetechPacket(b, d),
    createReader: (o: PacketReaderOptions) => createFeetechReader(o),
  },
};

for (const protocol of ['dynamixel', 'feetech'] as BusProtocol[]) {
  const codec = CODECS[protocol];

  describe(`${protocol} packets (vendors' documented examples first)`, () => {
    for (const v of codec.packets) {
      const wire = fromHex(v.hex);
      const packet = toPacket(v.packet);
      it(`${v.name}: decodes`, () => {
        expect(codec.decode(wire, v.direction ?? 'status')).toEqual(packet);
      });
      it(`${v.name}: encodes to the same bytes`, () => {
        expect(toHex(codec.encode(packet))).toBe(toHex(wire));
      });
      if (v.packet.type === 'instruction') {
        it(`${v.name}: ${v.unknown ? 'is an instruction this package does not run' : 'is the instruction'}`, () => {
          const decoded = decodeInstruction(
            protocol,
            packet as Extract<typeof packet, { type: 'instruction' }>,
          );
          if (v.unknown) {
            expect(decoded).toMatchObject({ ok: false, reason: 'unknown-instruction' });
            return;
          }
          expect(decoded).toEqual({ ok: true, instruction: toInstruction(v.instruction!) });
          expect(toHex(encodeInstruction(protocol, toInstruction(v.instruction!)))).toBe(
            toHex(wire),
          );
        });
      }
    }
  });

  describe(`${protocol} reader test vectors`, () => {
    for (const v of codec.reader) {
      const whole = fromHex(v.chunks.join(' '));
      const expected = { packets: v.packets.map(toPacket), errors: v.errors };
      const make = (o: PacketReaderOptions) =>
        codec.createReader({ ...o, ...(v.direction ? { direction: v.direction } : {}) });
      it(`${v.name}: as given`, () => {
        expect(collect(make, v.chunks.map(fromHex))).toEqual(expected);
      });
      it(`${v.name}: split at every byte offset`, () => {
        for (let cut = 0; cut <= whole.length; cut++)
          expect(collect(make, [whole.slice(0, cut), whole.slice(cut)]), `cut at ${cut}`).toEqual(
            expected,
          );
      });
      it(`${v.name}: one byte at a time`, () => {
        expect(
          collect(
            make,
            [...whole].map((b) => Uint8Array.of(b)),
          ),
        ).toEqual(expected);
      });
    }
  });
}

describe('reader API', () => {
  it('holds at most one packet and reports errors with the dropped bytes', () => {
    const errors: { kind: string; bytes: string }[] = [];
    const reader = createDynamixelReader({
      maxPacketLength: 16,
      onError: (e) => errors.push({ kind: e.kind, bytes: toHex(e.bytes) }),
    });
    reader.feed(fromHex('01 02 FF FF FD 00 01 03'));
    expect(reader.bufferedBytes).toBe(6);
    reader.feed(fromHex('00 01'));
    expect(reader.bufferedBytes).toBe(8);
    reader.reset();
    expect(reader.bufferedBytes).toBe(0);
    reader.feed(fromHex('FF FF FD 00 01 20 00'));
    expect(errors).toEqual([{ kind: 'too-long', bytes: 'FF FF FD 00 01 20 00' }]);
    expect(reader.bufferedBytes).toBe(0);
  });

  it('reports junk only once the run ends, with its bytes, capped at the bound', () => {
    const errors: string[] = [];
    const reader = createFeetechReader({
      maxPacketLength: 8,
      onError: (e) => errors.push(`${e.kind}: ${toHex(e.bytes)}`),
    });
    reader.feed(fromHex('00 01 02 03 04 05 06 07 08 09'));
    expect(errors).toEqual([]);
    reader.feed(fromHex('FF FF 01 02 00 FC'));
    expect(errors).toEqual(['junk: 00 01 02 03 04 05 06 07']);
  });

  it('a Feetech reader reads instructions when told to', () => {
    const { packets } = collect(
      (o) => createFeetechReader({ ...o, direction: 'instruction' }),
      [fromHex('FF FF 01 02 01 FB')],
    );
    expect(packets).toEqual([
      { type: 'instruction', id: 1, instruction: 1, params: new Uint8Array(0) },
    ]);
  });
});
