import { describe, expect, it } from 'vitest';
import {
  BUS_PROTOCOLS,
  BusError,
  createBusClient,
  createEmulatedBus,
  replyTimeoutMs,
  type BusClient,
  type BusResult,
  type EmulatedBus,
} from '../src/index.ts';

/** The client's request over the emulated bus and back, the answer cut into `chunks` pieces. */
function roundTrip(
  client: BusClient,
  bus: EmulatedBus,
  bytes: Uint8Array,
  chunks = 1,
): BusResult | undefined {
  const answer = bus.feed(bytes);
  const results: BusResult[] = [];
  const step = Math.ceil(answer.length / chunks) || 1;
  for (let at = 0; at < answer.length; at += step)
    results.push(...client.feed(answer.subarray(at, at + step)));
  expect(results.length).toBeLessThanOrEqual(1);
  return results[0] ?? client.expire();
}

const setup = (protocol: (typeof BUS_PROTOCOLS)[number]) => {
  const bus = createEmulatedBus({ protocol, servos: [{ id: 1 }, { id: 2, position: 1024 }] });
  const client = createBusClient({
    protocol,
    servos: [
      { id: 1 }, // zero at 2048, +1
      { id: 2, zeroTicks: 1024, direction: -1 },
      { id: 3 }, // configured but not on the bus
    ],
  });
  return { bus, client };
};

for (const protocol of BUS_PROTOCOLS) {
  describe(`bus client over an emulated ${protocol} bus`, () => {
    it('pings: found with the model number where the bus gives one; missing servos found false', () => {
      const { bus, client } = setup(protocol);
      const ping = roundTrip(client, bus, client.ping(1));
      expect(ping).toMatchObject({
        kind: 'ping',
        id: 1,
        found: true,
        status: { error: 0, problems: [] },
      });
      if (protocol === 'dynamixel') expect(ping).toMatchObject({ modelNumber: 1020 });
      expect(roundTrip(client, bus, client.ping(3))).toEqual({ kind: 'ping', id: 3, found: false });
      expect(roundTrip(client, bus, client.readModel(2))).toMatchObject({
        kind: 'model',
        found: true,
        modelName: protocol === 'dynamixel' ? 'XM430-W350' : 'STS3215',
      });
    });

    it('reads all positions in one sync read, in degrees after zero and direction; the absent one is missing', () => {
      const { bus, client } = setup(protocol);
      const bytes = client.readPositions();
      expect(client.pending).toMatchObject({ kind: 'positions', ids: [1, 2, 3] });
      expect(roundTrip(client, bus, bytes)).toEqual({
        kind: 'positions',
        servos: [
          { id: 1, ticks: 2048, degrees: 0, status: { error: 0, problems: [] } },
          { id: 2, ticks: 1024, degrees: -0, status: { error: 0, problems: [] } },
        ],
        missing: [3],
      });
      expect(client.counters.expired).toBe(1);
      expect(client.pending).toBeUndefined();
    });

    it('completes as soon as the last answer arrives, however the bytes are cut', () => {
      const { bus, client } = setup(protocol);
      for (const chunks of [1, 2, 3, 7, 40]) {
        const result = roundTrip(client, bus, client.readPositions([2, 1]), chunks);
        expect(result).toMatchObject({ kind: 'positions', missing: [] });
      }
      expect(client.counters.expired).toBe(0);
    });

    it('reads temperature and voltage of all servos', () => {
      const { bus, client } = setup(protocol);
      bus.servo(2)!.setTemperature(47);
      bus.servo(2)!.setVoltage(11.3);
      const health = roundTrip(client, bus, client.readHealth([1, 2]));
      expect(health).toMatchObject({
        kind: 'health',
        missing: [],
        servos: [{ id: 1 }, { id: 2, temperatureC: 47, voltageV: 11.3 }],
      });
    });

    it('torque on, goals in degrees with a speed: the servos get there, positions read back in degrees', () => {
      const { bus, client } = setup(protocol);
      expect(bus.feed(client.setTorque(true, [1, 2]))).toHaveLength(0);
      expect(client.pending).toBeUndefined();
      bus.feed(
        client.writeGoals(
          [
            { id: 1, degrees: 90 },
            { id: 2, degrees: 45 },
          ],
          { speedDegPerS: 90 },
        ),
      );
      expect(bus.servo(1)!.goal).toBe(3072);
      expect(bus.servo(2)!.goal).toBe(1024 - 512);
      bus.advance(500);
      const halfway = roundTrip(client, bus, client.readPositions([1, 2]));
      expect(halfway?.kind === 'positions' && halfway.servos[0]!.degrees).toBeCloseTo(45, 0);
      bus.advance(1100);
      const there = roundTrip(client, bus, client.readPositions([1, 2]));
      expect(there).toMatchObject({
        servos: [
          { id: 1, degrees: 90 },
          { id: 2, degrees: 45 },
        ],
      });
    });

    it('one request at a time; a write is acknowledged', () => {
      const { bus, client } = setup(protocol);
      client.ping(1);
      expect(() => client.readPositions()).toThrow(BusError);
      client.expire();
      const ack = roundTrip(
        client,
        bus,
        client.write(1, protocol === 'dynamixel' ? 65 : 41, Uint8Array.of(1)),
      );
      expect(ack).toEqual({
        kind: 'write',
        id: 1,
        found: true,
        status: { error: 0, problems: [] },
      });
    });

    it('refuses goals the bus cannot carry and servos it does not know', () => {
      const { client } = setup(protocol);
      expect(() => client.writeGoals([{ id: 9, degrees: 0 }])).toThrow(/not on this bus client/);
      if (protocol === 'feetech')
        expect(() => client.writeGoals([{ id: 1, degrees: 3000 }])).toThrow(/32767/);
    });
  });
}

describe('bus client details', () => {
  it('Dynamixel: a goal with a speed is one 8-byte sync write of Profile Velocity and Goal Position', () => {
    const client = createBusClient({ protocol: 'dynamixel', servos: [{ id: 1 }] });
    const bus = createEmulatedBus({ protocol: 'dynamixel', servos: [{ id: 1 }] });
    bus.feed(client.writeGoals([{ id: 1, degrees: -90 }], { speedDegPerS: 68.7 })); // 68.7 °/s = 11.45 rev/min = 50 units
    expect(bus.servo(1)!.field('profileVelocity')).toBe(50);
    expect(bus.servo(1)!.goal).toBe(1024);
  });

  it('Feetech: status error flags come back as problems', () => {
    const client = createBusClient({ protocol: 'feetech', servos: [{ id: 1 }] });
    const bus = createEmulatedBus({ protocol: 'feetech', servos: [{ id: 1, temperatureC: 80 }] });
    expect(roundTrip(client, bus, client.readHealth())).toMatchObject({
      servos: [{ id: 1, temperatureC: 80, status: { error: 4, problems: ['overheat'] } }],
    });
  });

  it('an answer held behind a false header is read when the wait expires', () => {
    const client = createBusClient({ protocol: 'feetech', servos: [{ id: 1 }] });
    const bus = createEmulatedBus({ protocol: 'feetech', servos: [{ id: 1 }] });
    const answer = bus.feed(client.ping(1));
    expect(client.feed(Uint8Array.of(0xff, 0xff, 0x00, 0x30, 0x00))).toEqual([]); // noise: a header claiming 48 bytes
    expect(client.feed(answer)).toEqual([]);
    expect(client.expire()).toMatchObject({ kind: 'ping', id: 1, found: true });
    expect(client.counters.errors.truncated).toBe(1);
  });

  it('reply timeout: transfer time at the baud rate plus a margin', () => {
    const client = createBusClient({ protocol: 'dynamixel', servos: [{ id: 1 }, { id: 2 }] });
    client.readPositions();
    expect(client.pending!.expectedReplyBytes).toBe(2 * 15);
    expect(replyTimeoutMs(client.pending!.expectedReplyBytes, 57_600)).toBeCloseTo(
      (30 * 10) / 57.6 + 40,
      6,
    );
  });
});
