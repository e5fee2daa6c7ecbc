import { describe, expect, it } from 'vitest';
import {
  createEmulatedBus,
  decodeField,
  fromHex,
  readUnsigned,
  STS_TABLE as T,
  statusProblems,
} from '../src/index.ts';
import { le16, reply, send, u8 } from './host.ts';

const twoServos = () =>
  createEmulatedBus({
    protocol: 'feetech',
    servos: [{ id: 1 }, { id: 2, position: 1000, voltageV: 12.1 }],
  });
const position = (bus: ReturnType<typeof twoServos>, id: number) =>
  decodeField(T.presentPosition, reply(bus, { op: 'read', id, address: 56, length: 2 }).params);

describe('emulated Feetech STS bus', () => {
  it("answers the manual's PING packet; the model number (777, STS3215) is at address 3", () => {
    const bus = twoServos();
    expect(reply(bus, fromHex('FF FF 01 02 01 FB'))).toEqual({
      type: 'status',
      id: 1,
      error: 0,
      params: u8(),
    });
    expect(
      readUnsigned(reply(bus, { op: 'read', id: 1, address: 3, length: 2 }).params, 0, 2),
    ).toBe(777);
    expect(send(bus, { op: 'ping', id: 9 })).toEqual([]);
  });

  it("answers the manual's SYNC READ of 8 bytes at 0x38: position, speed, load, voltage, temperature", () => {
    const bus = twoServos();
    bus.servo(1)!.setTemperature(30);
    const replies = send(bus, fromHex('FF FF FE 06 82 38 08 01 02 36'));
    expect(replies.map((r) => [r.id, [...r.params]])).toEqual([
      [1, [0x00, 0x08, 0, 0, 0, 0, 74, 30]],
      [2, [0xe8, 0x03, 0, 0, 0, 0, 121, 25]],
    ]);
  });

  it('moves at Goal Speed (steps/s) once torque is on; Moving and Present Speed follow', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 40, data: u8(1) });
    reply(bus, { op: 'write', id: 1, address: 42, data: u8(0x00, 0x0c, 0, 0, 0xe8, 0x03) }); // 3072, time 0, 1000 steps/s
    bus.advance(500);
    expect(position(bus, 1)).toBe(2548);
    expect(reply(bus, { op: 'read', id: 1, address: 58, length: 2 }).params).toEqual(le16(1000));
    expect(reply(bus, { op: 'read', id: 1, address: 66, length: 1 }).params).toEqual(u8(1));
    bus.advance(1100);
    expect(position(bus, 1)).toBe(3072);
    expect(reply(bus, { op: 'read', id: 1, address: 66, length: 1 }).params).toEqual(u8(0));
  });

  it('clamps goals to the angle limits; with both limits 0 it turns many times, negative in sign-magnitude', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 40, data: u8(1) });
    reply(bus, { op: 'write', id: 1, address: 11, data: le16(3000) });
    reply(bus, { op: 'write', id: 1, address: 42, data: le16(4000) });
    expect(bus.servo(1)!.goal).toBe(3000);
    reply(bus, { op: 'write', id: 1, address: 9, data: u8(0, 0, 0, 0) });
    reply(bus, { op: 'write', id: 1, address: 42, data: le16(500 | 0x8000) }); // −500
    bus.advance(10_000);
    const raw = reply(bus, { op: 'read', id: 1, address: 56, length: 2 }).params;
    expect(raw).toEqual(le16(500 | 0x8000));
    expect(position(bus, 1)).toBe(-500);
  });

  it('Torque Enable 128 makes the present position read 2048 (homing offset)', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 2, address: 40, data: u8(128) });
    expect(position(bus, 2)).toBe(2048);
    expect(bus.servo(2)!.field('homingOffset')).toBe(1000 - 2048);
  });

  it('broadcasts: PING answered by all in id order, WRITE by none', () => {
    const bus = twoServos();
    expect(send(bus, { op: 'ping', id: 254 }).map((s) => s.id)).toEqual([1, 2]);
    expect(send(bus, fromHex('FF FF FE 02 05 FA'))).toEqual([]); // ACTION
    expect(
      send(bus, { op: 'sync-write', address: 40, length: 1, writes: [{ id: 1, data: u8(1) }] }),
    ).toEqual([]);
    expect(bus.servo(1)!.torque).toBe(true);
  });

  it('Response Status Level 0: only PING and READ are answered', () => {
    const bus = twoServos();
    send(bus, { op: 'write', id: 1, address: 8, data: u8(0) });
    expect(send(bus, { op: 'write', id: 1, address: 41, data: u8(10) })).toEqual([]);
    expect(reply(bus, { op: 'read', id: 1, address: 41, length: 1 }).params).toEqual(u8(10));
  });

  it('health flags in every status; overheating drops torque (Unloading Condition)', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 40, data: u8(1) });
    bus.servo(1)!.setTemperature(75); // limit 70 °C
    bus.servo(1)!.setVoltage(3.5); // limit 4.0 V
    expect(statusProblems('feetech', reply(bus, { op: 'ping', id: 1 }).error)).toEqual([
      'voltage',
      'overheat',
    ]);
    expect(bus.servo(1)!.torque).toBe(false);
  });

  it('a packet with a bad checksum gets no answer', () => {
    const bus = twoServos();
    expect(send(bus, fromHex('FF FF 01 02 01 FA'))).toEqual([]);
    expect(bus.counters.errors['bad-checksum']).toBe(1);
  });
});
