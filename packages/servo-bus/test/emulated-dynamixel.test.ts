import { describe, expect, it } from 'vitest';
import {
  createEmulatedBus,
  decodeField,
  fromHex,
  readUnsigned,
  statusProblems,
  toSigned,
  X_SERIES_TABLE as T,
} from '../src/index.ts';
import { le16, le32, reply, send, u8 } from './host.ts';

const twoServos = () =>
  createEmulatedBus({
    protocol: 'dynamixel',
    servos: [{ id: 1 }, { id: 2, model: 'XL430-W250', position: 1000 }],
  });
const read4 = (bus: ReturnType<typeof twoServos>, id: number, address: number) =>
  toSigned(readUnsigned(reply(bus, { op: 'read', id, address, length: 4 }).params, 0, 4), 4);
const problems = (error: number) => statusProblems('dynamixel', error);

describe('emulated Dynamixel bus', () => {
  it('answers the e-Manual PING packet with the model number and firmware', () => {
    const bus = twoServos();
    const status = reply(bus, fromHex('FF FF FD 00 01 03 00 01 19 4E'));
    expect(status).toEqual({ type: 'status', id: 1, error: 0, params: u8(0xfc, 0x03, 46) }); // 1020: XM430-W350
    expect(reply(bus, { op: 'ping', id: 2 }).params.slice(0, 2)).toEqual(le16(1060)); // XL430-W250
  });

  it('answers only the addressed servo; nobody answers an id not on the bus', () => {
    const bus = twoServos();
    expect(send(bus, { op: 'ping', id: 3 })).toEqual([]);
    expect(bus.counters.ignored).toBe(1);
  });

  it('answers a broadcast PING from every servo in id order, and nothing else broadcast', () => {
    const bus = twoServos();
    expect(send(bus, { op: 'ping', id: 254 }).map((s) => s.id)).toEqual([1, 2]);
    expect(send(bus, { op: 'write', id: 254, address: T.led.address, data: u8(1) })).toEqual([]);
    expect(bus.servos.map((s) => s.field('led'))).toEqual([1, 1]);
  });

  it('reads the control table: present position, voltage and temperature', () => {
    const bus = twoServos();
    expect(read4(bus, 1, 132)).toBe(2048);
    expect(read4(bus, 2, 132)).toBe(1000);
    bus.servo(1)!.setVoltage(11.6);
    bus.servo(1)!.setTemperature(41);
    const health = reply(bus, { op: 'read', id: 1, address: 144, length: 3 }).params;
    expect(readUnsigned(health, 0, 2)).toBe(116);
    expect(health[2]).toBe(41);
    expect(problems(reply(bus, { op: 'read', id: 1, address: 250, length: 10 }).error)).toEqual([
      'access',
    ]);
  });

  it('moves to the goal at the profile velocity once torque is on, as time advances', () => {
    const bus = twoServos();
    expect(reply(bus, { op: 'write', id: 1, address: 116, data: le32(3072) }).error).toBe(0);
    bus.advance(1000);
    expect(read4(bus, 1, 132)).toBe(2048); // torque off: nothing moves
    reply(bus, { op: 'write', id: 1, address: 112, data: le32(100) }); // 22.9 rev/min ≈ 1563 ticks/s
    reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) });
    bus.advance(1300);
    expect(read4(bus, 1, 132)).toBe(2048 + Math.round(((100 * 0.229 * 4096) / 60) * 0.3));
    expect(reply(bus, { op: 'read', id: 1, address: 122, length: 1 }).params).toEqual(u8(1));
    expect(read4(bus, 1, 128)).toBe(100); // present velocity, 0.229 rev/min units
    bus.advance(2000);
    expect(read4(bus, 1, 132)).toBe(3072);
    expect(reply(bus, { op: 'read', id: 1, address: 122, length: 1 }).params).toEqual(u8(0));
  });

  it('moves at the velocity limit when the profile velocity is 0', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) });
    reply(bus, { op: 'write', id: 1, address: 116, data: le32(3072) });
    bus.advance(100);
    expect(read4(bus, 1, 132)).toBe(2048 + Math.round(((167 * 0.229 * 4096) / 60) * 0.1)); // XM430-W350: 167
  });

  it('SYNC READ: each listed servo answers, in the order listed; SYNC WRITE: no answer, all move', () => {
    const bus = twoServos();
    const replies = send(bus, { op: 'sync-read', address: 132, length: 4, ids: [2, 3, 1] });
    expect(replies.map((r) => [r.id, readUnsigned(r.params, 0, 4)])).toEqual([
      [2, 1000],
      [1, 2048],
    ]);
    expect(
      send(bus, {
        op: 'sync-write',
        address: 64,
        length: 1,
        writes: [
          { id: 1, data: u8(1) },
          { id: 2, data: u8(1) },
        ],
      }),
    ).toEqual([]);
    expect(
      send(bus, {
        op: 'sync-write',
        address: 116,
        length: 4,
        writes: [
          { id: 1, data: le32(2100) },
          { id: 2, data: le32(900) },
        ],
      }),
    ).toEqual([]);
    bus.advance(5000);
    expect([read4(bus, 1, 132), read4(bus, 2, 132)]).toEqual([2100, 900]);
  });

  it('refuses what the e-Manual says a servo refuses, and writes nothing then', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) });
    // EEPROM with torque on
    expect(problems(reply(bus, { op: 'write', id: 1, address: 11, data: u8(4) }).error)).toEqual([
      'access',
    ]);
    // beyond Max Position Limit in position mode
    expect(
      problems(reply(bus, { op: 'write', id: 1, address: 116, data: le32(5000) }).error),
    ).toEqual(['data-limit']);
    // half a 4-byte field
    expect(
      problems(reply(bus, { op: 'write', id: 1, address: 116, data: le16(100) }).error),
    ).toEqual(['data-length']);
    // read-only
    expect(problems(reply(bus, { op: 'write', id: 1, address: 132, data: le32(0) }).error)).toEqual(
      ['access'],
    );
    expect(bus.servo(1)!.goal).toBe(2048);
    // an instruction it does not run (FACTORY_RESET, e-Manual example)
    expect(problems(reply(bus, fromHex('FF FF FD 00 01 04 00 06 01 A1 E6')).error)).toEqual([
      'instruction',
    ]);
    // a CRC that does not match
    expect(problems(reply(bus, fromHex('FF FF FD 00 01 03 00 01 19 4F')).error)).toEqual(['crc']);
  });

  it('extended position mode (4) turns past one turn in both directions', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 11, data: u8(4) });
    reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) });
    expect(reply(bus, { op: 'write', id: 1, address: 116, data: le32(-4096) }).error).toBe(0);
    bus.advance(10_000);
    expect(read4(bus, 1, 132)).toBe(-4096);
  });

  it('overheating: alert bit on every status, torque off, no torque until a REBOOT after cooling', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) });
    bus.servo(1)!.setTemperature(85); // XM430-W350 limit: 80 °C
    expect(bus.servo(1)!.torque).toBe(false);
    const status = reply(bus, { op: 'read', id: 1, address: 70, length: 1 });
    expect(problems(status.error)).toEqual(['hardware-alert']);
    expect(status.params).toEqual(u8(0x04)); // Hardware Error Status: overheating
    expect(problems(reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) }).error)).toEqual([
      'result-fail',
      'hardware-alert',
    ]);
    bus.servo(1)!.setTemperature(40);
    reply(bus, { op: 'reboot', id: 1 });
    expect(reply(bus, { op: 'write', id: 1, address: 64, data: u8(1) }).error).toBe(0);
  });

  it('Status Return Level 1: READ is answered, WRITE is not', () => {
    const bus = twoServos();
    send(bus, { op: 'write', id: 1, address: 68, data: u8(1) });
    expect(send(bus, { op: 'write', id: 1, address: 65, data: u8(1) })).toEqual([]);
    expect(reply(bus, { op: 'read', id: 1, address: 65, length: 1 }).params).toEqual(u8(1));
  });

  it('REG_WRITE waits for ACTION', () => {
    const bus = twoServos();
    reply(bus, { op: 'reg-write', id: 2, address: 65, data: u8(1) });
    expect(bus.servo(2)!.field('led')).toBe(0);
    expect(bus.servo(2)!.field('registeredInstruction')).toBe(1);
    send(bus, { op: 'action', id: 254 });
    expect(bus.servo(2)!.field('led')).toBe(1);
  });

  it('a new ID takes effect at once', () => {
    const bus = twoServos();
    reply(bus, { op: 'write', id: 2, address: 7, data: u8(7) });
    expect(send(bus, { op: 'ping', id: 2 })).toEqual([]);
    expect(reply(bus, { op: 'ping', id: 7 }).id).toBe(7);
  });

  it('the simulator can move the shaft (torque off: it stays there)', () => {
    const bus = twoServos();
    bus.servo(1)!.setPosition(2500);
    bus.advance(100);
    expect(
      decodeField(
        T.presentPosition,
        reply(bus, { op: 'read', id: 1, address: 132, length: 4 }).params,
      ),
    ).toBe(2500);
  });
});
