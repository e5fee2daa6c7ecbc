/**
 * A hand on the emulated bus (`armtwin sim --bus … --hand`): the line format, and a shaft put
 * where the hand says as the bus client then reads it (torque off: it stays; torque on: the
 * servo goes back to its goal, as a real one would).
 */
import { describe, expect, test } from 'vitest';
import { createBusClient, type BusResult } from '@armtwin/servo-bus';
import { BusSimCore, loadSimProfile, parseHandLine } from '../src/index.ts';

describe('parseHandLine', () => {
  test('ID:DEGREES pairs, comma- or space-separated; blank is nothing', () => {
    expect(parseHandLine('1:30,2:-15.5 6:+40')).toEqual([
      { id: 1, degrees: 30 },
      { id: 2, degrees: -15.5 },
      { id: 6, degrees: 40 },
    ]);
    expect(parseHandLine('   ')).toEqual([]);
  });

  test('a bad move says which and what is expected', () => {
    expect(() => parseHandLine('1:30,x')).toThrow(/"x" is not ID:DEGREES/);
    expect(() => parseHandLine('300:1')).toThrow(/servo id 300/);
    expect(() => parseHandLine('1:4000')).toThrow(/past ±3600°/);
  });
});

describe('BusSimCore.hand', () => {
  const profile = loadSimProfile('so101').profile;
  const ids = profile.servos.map((s) => s.id);
  const sim = new BusSimCore({ protocol: 'feetech', profile }, 0);
  const client = createBusClient({ protocol: 'feetech', servos: ids.map((id) => ({ id })) });
  let now = 0;
  const ask = (bytes: Uint8Array): BusResult | undefined =>
    client.feed(sim.feed(bytes, now))[0] ?? client.expire();
  const pan = () => {
    const r = ask(client.readPositions([1]));
    return r?.kind === 'positions' ? r.servos[0]!.degrees : NaN;
  };

  test('torque off: the shaft stays where the hand put it; an unknown servo is refused', () => {
    ask(client.setTorque(false, ids));
    expect(sim.hand({ id: 1, degrees: -20 }, (now += 10))).toBe(true);
    now += 500;
    expect(pan()).toBeCloseTo(-20, 1);
    expect(sim.hand({ id: 9, degrees: 5 }, now)).toBe(false);
  });

  test('torque on: the servo turns back to its goal', () => {
    ask(client.writeGoals([{ id: 1, degrees: 0 }], { speedDegPerS: 500 }));
    ask(client.setTorque(true, [1]));
    sim.hand({ id: 1, degrees: 30 }, (now += 10));
    now += 1000;
    expect(pan()).toBeCloseTo(0, 1);
  });
});
