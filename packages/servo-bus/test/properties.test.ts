import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  BUS_PROTOCOLS,
  createPacketReader,
  decodeField,
  decodeInstruction,
  degreesToTicks,
  encodeField,
  encodeInstruction,
  encodePacket,
  fieldRange,
  STS_TABLE,
  ticksToDegrees,
  X_SERIES_TABLE,
  type BusProtocol,
  type Field,
  type Instruction,
  type Packet,
} from '../src/index.ts';

/** Bytes that make framing hard: headers, stuffing, the FF run. */
const NASTY_BYTE = fc.oneof(
  fc.constantFrom(0xff, 0xfd, 0x00, 0x55, 0xfe),
  fc.integer({ min: 0, max: 255 }),
);
const bytes = (maxLength: number) =>
  fc.array(NASTY_BYTE, { maxLength }).map((a) => Uint8Array.from(a));
const idFor = (protocol: BusProtocol) =>
  protocol === 'dynamixel'
    ? fc.oneof(fc.integer({ min: 0, max: 0xfc }), fc.constant(0xfe))
    : fc.integer({ min: 0, max: 0xfe });

function packetArb(
  protocol: BusProtocol,
  direction: 'instruction' | 'status',
): fc.Arbitrary<Packet> {
  const maxParams = protocol === 'dynamixel' ? 120 : 60;
  return direction === 'status'
    ? fc.record({
        type: fc.constant('status' as const),
        id: idFor(protocol),
        error: fc.integer({ min: 0, max: 255 }),
        params: bytes(maxParams),
      })
    : fc.record({
        type: fc.constant('instruction' as const),
        id: idFor(protocol),
        // 0x55 is a status packet on Dynamixel
        instruction: fc
          .integer({ min: 0, max: 255 })
          .filter((n) => protocol !== 'dynamixel' || n !== 0x55),
        params: bytes(maxParams),
      });
}

/** Splits bytes into chunks at random offsets. */
const chunked = (all: Uint8Array, cuts: number[]) => {
  const at = [...new Set(cuts.map((c) => c % (all.length + 1)))].sort((a, b) => a - b);
  const out: Uint8Array[] = [];
  let prev = 0;
  for (const c of [...at, all.length]) {
    out.push(all.slice(prev, c));
    prev = c;
  }
  return out;
};

function read(protocol: BusProtocol, direction: 'instruction' | 'status', chunks: Uint8Array[]) {
  const packets: Packet[] = [];
  const errors: string[] = [];
  const reader = createPacketReader(protocol, {
    direction,
    onPacket: (p) => packets.push(p),
    onError: (e) => errors.push(e.kind),
  });
  for (const c of chunks) reader.feed(c);
  reader.flush();
  return { packets, errors };
}

for (const protocol of BUS_PROTOCOLS) {
  describe(`${protocol} properties`, () => {
    for (const direction of ['instruction', 'status'] as const) {
      it(`${direction} packets: encode → read gives them back, however the bytes are cut`, () => {
        fc.assert(
          fc.property(
            fc.array(packetArb(protocol, direction), { minLength: 1, maxLength: 6 }),
            fc.array(fc.nat(), { maxLength: 8 }),
            (packets, cuts) => {
              const wire = packets.map((p) => encodePacket(protocol, p));
              const all = new Uint8Array(wire.reduce((n, w) => n + w.length, 0));
              let at = 0;
              for (const w of wire) {
                all.set(w, at);
                at += w.length;
              }
              expect(read(protocol, direction, chunked(all, cuts))).toEqual({
                packets,
                errors: [],
              });
            },
          ),
          { numRuns: 300 },
        );
      });
    }

    it('random bytes never throw and never grow the buffer past its bound', () => {
      fc.assert(
        fc.property(fc.array(bytes(400), { maxLength: 12 }), (chunks) => {
          const reader = createPacketReader(protocol, {
            maxPacketLength: 200,
            onError: (e) => expect(e.bytes.length).toBeLessThanOrEqual(200),
          });
          for (const c of chunks) {
            reader.feed(c);
            expect(reader.bufferedBytes).toBeLessThanOrEqual(200);
          }
          reader.flush();
          expect(reader.bufferedBytes).toBe(0);
        }),
        { numRuns: 300 },
      );
    });

    it('a good packet after junk is still found', () => {
      fc.assert(
        fc.property(bytes(60), packetArb(protocol, 'status'), (junk, packet) => {
          // A false header in the junk may claim up to a packet's bound; zeros beyond that end it.
          const gap = new Uint8Array((protocol === 'dynamixel' ? 1024 : 250) + 8);
          const wire = encodePacket(protocol, packet);
          const all = new Uint8Array([...junk, ...gap, ...wire]);
          const { packets } = read(protocol, 'status', [all]);
          expect(packets.at(-1)).toEqual(packet);
        }),
        { numRuns: 300 },
      );
    });

    it('instructions: encode → decode gives them back', () => {
      const id = fc.integer({ min: 0, max: 0xfc });
      const address = fc.integer({ min: 0, max: protocol === 'dynamixel' ? 0xffff : 0xff });
      const data = fc
        .array(NASTY_BYTE, { minLength: 1, maxLength: 8 })
        .map((a) => Uint8Array.from(a));
      const ins: fc.Arbitrary<Instruction> = fc.oneof(
        fc.record({ op: fc.constant('ping' as const), id }),
        fc.record({
          op: fc.constant('read' as const),
          id,
          address,
          length: fc.integer({ min: 1, max: 200 }),
        }),
        fc.record({ op: fc.constant('write' as const), id, address, data }),
        fc.record({ op: fc.constant('reg-write' as const), id, address, data }),
        fc.record({ op: fc.constant('action' as const), id }),
        fc.record({
          op: fc.constant('sync-read' as const),
          address,
          length: fc.integer({ min: 1, max: 8 }),
          ids: fc.uniqueArray(id, { maxLength: 10 }),
        }),
        fc.integer({ min: 1, max: 6 }).chain((length) =>
          fc.record({
            op: fc.constant('sync-write' as const),
            address,
            length: fc.constant(length),
            writes: fc.array(
              fc.record({
                id,
                data: fc
                  .array(NASTY_BYTE, { minLength: length, maxLength: length })
                  .map((a) => Uint8Array.from(a)),
              }),
              { maxLength: 8 },
            ),
          }),
        ),
      );
      fc.assert(
        fc.property(ins, (instruction) => {
          const { packets } = read(protocol, 'instruction', [
            encodeInstruction(protocol, instruction),
          ]);
          expect(packets).toHaveLength(1);
          expect(
            decodeInstruction(protocol, packets[0] as Extract<Packet, { type: 'instruction' }>),
          ).toEqual({ ok: true, instruction });
        }),
        { numRuns: 300 },
      );
    });
  });
}

describe('field values', () => {
  const fields: [string, Field][] = [
    ...Object.entries(X_SERIES_TABLE),
    ...Object.entries(STS_TABLE),
  ];
  it('every field of both tables: encode → decode gives the value back over its whole range', () => {
    for (const [name, field] of fields) {
      const { min, max } = fieldRange(field);
      fc.assert(
        fc.property(fc.integer({ min, max }), (value) => {
          expect(decodeField(field, encodeField(field, value, name)), name).toBe(value);
        }),
        { numRuns: 50 },
      );
    }
  });

  it("Feetech positions use bit 15 as the sign, as the SDK's SCS_TOSCS does", () => {
    expect([...encodeField(STS_TABLE.goalPosition, -500)]).toEqual([0xf4, 0x81]); // 500 | 0x8000
    expect(decodeField(STS_TABLE.presentLoad, Uint8Array.of(0x64, 0x04))).toBe(-100); // bit 10
    expect(() => encodeField(STS_TABLE.goalPosition, 32768)).toThrow(/32767/);
  });

  it("Dynamixel positions are two's complement", () => {
    expect([...encodeField(X_SERIES_TABLE.goalPosition, -3)]).toEqual([0xfd, 0xff, 0xff, 0xff]);
  });
});

describe('degrees ↔ ticks', () => {
  it('round trips within half a tick, for any zero and direction', () => {
    fc.assert(
      fc.property(
        fc.double({ min: -720, max: 720, noNaN: true }),
        fc.integer({ min: 0, max: 4095 }),
        fc.constantFrom(1 as const, -1 as const),
        (degrees, zeroTicks, direction) => {
          const cal = { id: 1, zeroTicks, direction };
          expect(
            Math.abs(ticksToDegrees(degreesToTicks(degrees, cal), cal) - degrees),
          ).toBeLessThanOrEqual(180 / 4096 + 1e-9);
        },
      ),
    );
  });

  it('uses the zero and the direction', () => {
    expect(ticksToDegrees(3072, { id: 1 })).toBe(90);
    expect(ticksToDegrees(3072, { id: 1, direction: -1 })).toBe(-90);
    expect(degreesToTicks(-90, { id: 1, zeroTicks: 1000, direction: -1 })).toBe(2024);
  });
});
