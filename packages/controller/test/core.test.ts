/**
 * The controller core on a driver of plain arrays (positions jump to their goal after the goal's
 * time), time handed in as numbers: what reaches the driver, what is answered, what is counted.
 * Limits, a group all or nothing, the keep-out rules, `$KMS` and its codes, the e-stop, the
 * deadman, an unready driver, the rate limit and the payload bound in front of the core.
 */
import { describe, expect, test } from 'vitest';
import { DEMO_ARM } from '@armtwin/ik';
import {
  ControlInput,
  ControllerCore,
  jointsFromArm,
  type KeepOutCheck,
  type KmsSolver,
} from '../src/index.ts';
import { ArrayDriver } from './array-driver.ts';

/** Refuses any goal of servo 000 past 2000 µs as a zone, below 1000 µs as the floor. */
const keepOut: KeepOutCheck = (_from, to) =>
  to[0]! > 2000 ? 'zone: hand in "wall"' : to[0]! < 1000 ? 'floor: tip below the floor' : '';

function rig(kms?: KmsSolver) {
  const driver = new ArrayDriver();
  const core = new ControllerCore(jointsFromArm(DEMO_ARM), driver, { keepOut, kms });
  const run = (frames: string, t = 0) => new ControlInput(core, {}, t).receive(frames, t);
  return { driver, core, run };
}

describe('the controller core', () => {
  test('a move within limits becomes goals; past a limit it is refused and counted', () => {
    const r = rig();
    expect(r.run('#001P1700T0500!')).toEqual([]);
    expect(r.driver.moves).toEqual([[{ i: 1, pwm: 1700, ms: 500 }]]);
    expect(r.run('#005P1000T0100!')).toEqual([
      expect.stringMatching(/^\$ERR:limit 005 P1000 outside \d+-\d+!$/),
    ]);
    expect(r.run('#009P1500T0100!')).toEqual(['$ERR:no servo 009!']);
    expect(r.driver.moves).toHaveLength(1);
    expect(r.core.counters.rejected).toMatchObject({ limit: 1, 'unknown-servo': 1 });
  });

  test('a group runs together or not at all', () => {
    const r = rig();
    r.run('{#001P1600T0200!#002P1400T0200!}');
    expect(r.driver.moves).toEqual([
      [
        { i: 1, pwm: 1600, ms: 200 },
        { i: 2, pwm: 1400, ms: 200 },
      ],
    ]);
    expect(r.run('{#001P1500T0200!#005P1000T0200!}')).toEqual([
      expect.stringMatching(/^\$ERR:group rejected: limit 005/),
    ]);
    expect(r.driver.moves).toHaveLength(1);
    expect(r.core.counters).toMatchObject({ groups: 1, rejected: { group: 1, limit: 1 } });
  });

  test('the keep-out rules refuse a move, counted as zone or floor, with the reason kept', () => {
    const r = rig();
    expect(r.run('#000P2100T0100!')).toEqual(['$ERR:zone: hand in "wall"!']);
    expect(r.run('#000P0900T0100!')).toEqual(['$ERR:floor: tip below the floor!']);
    expect(r.driver.moves).toEqual([]);
    expect(r.core.counters.rejected).toMatchObject({ zone: 1, floor: 1 });
    expect(r.core.lastKeepOutRefusal).toBe('floor: tip below the floor');
  });

  test('$KMS: 0 moves every servo solved together; past a limit 8, into a zone 25, unsolved its code', () => {
    let answer: number[] = [1600, 1550, NaN, NaN, NaN, NaN];
    let code = 0;
    const r = rig(() => ({ code, pwm: answer }));
    expect(r.run('$KMS:100,0,50,800!')).toEqual(['$KMS:0!']);
    expect(r.driver.moves).toEqual([
      [
        { i: 0, pwm: 1600, ms: 800 },
        { i: 1, pwm: 1550, ms: 800 },
      ],
    ]);
    answer = [1500, 3000, NaN, NaN, NaN, NaN];
    expect(r.run('$KMS:100,0,50,800!')).toEqual(['$KMS:8!']);
    answer = [2100, 1500, NaN, NaN, NaN, NaN];
    expect(r.run('$KMS:100,0,50,800!')).toEqual(['$KMS:25!']);
    code = 2;
    expect(r.run('$KMS:900,0,50,800!')).toEqual(['$KMS:2!']);
    expect(r.driver.moves).toHaveLength(1);
    expect(r.core.counters.rejected).toMatchObject({ zone: 1, ik: 1 });
  });

  test('without a solver $KMS is refused', () => {
    expect(rig().run('$KMS:100,0,50,800!')).toEqual(['$ERR:kms: no IK for this profile!']);
  });

  test('#255PDST! holds every servo; #001PDST! that one', () => {
    const r = rig();
    r.run('#001PDST!');
    r.run('#255PDST!');
    expect(r.driver.holds).toEqual([[1], [0, 1, 2, 3, 4, 5]]);
    expect(r.core.counters).toMatchObject({ stops: 1, emergencyStops: 1 });
  });

  test('the deadman holds a moving arm and says so; at rest it does nothing', () => {
    const r = rig();
    const out: string[] = [];
    expect(r.core.operatorLeft(0, out)).toBe(false);
    r.run('#000P1900T2000!', 0);
    expect(r.core.operatorLeft(1000, out)).toBe(true);
    expect(out).toEqual(['$ERR:deadman stop!']);
    expect(r.driver.holds).toEqual([[0, 1, 2, 3, 4, 5]]);
    expect(r.core.counters).toMatchObject({ deadmanStops: 1, emergencyStops: 1 });
  });

  test('a driver not ready refuses moves, stops and $KMS, but answers pings and reads', () => {
    const r = rig();
    r.driver.notReady = 'gateway: serial line down';
    expect(r.run('#001P1600T0100!$PNG:3!#002PRAD!')).toEqual([
      '$ERR:gateway: serial line down!',
      '$PNG:3!',
      '#002P1500!',
    ]);
    expect(r.run('#002PRTV!')).toEqual(['$ERR:no health!']);
    expect(r.core.counters.rejected).toMatchObject({ 'not-ready': 1, 'no-reading': 1 });
  });
});

describe('the control input in front of the core', () => {
  test('commands over the rate are dropped, the first of a run answered; stops always pass', () => {
    const r = rig();
    const input = new ControlInput(r.core, { commandRate: 10, commandBurst: 2 }, 0);
    const replies = input.receive(
      '#001P1600T0100!#001P1610T0100!#001P1620T0100!#001P1630T0100!#255PDST!',
      0,
    );
    expect(replies).toEqual(['$ERR:rate limit!']);
    expect(r.driver.moves).toHaveLength(2);
    expect(r.driver.holds).toHaveLength(1);
    expect(input.rateLimited).toBe(2);
    expect(input.receive('#001P1640T0100!', 100)).toEqual([]); // a token back after 100 ms
    expect(r.driver.moves).toHaveLength(3);
  });

  test('a payload over the bound is refused whole; bad frames are answered and counted', () => {
    const r = rig();
    const input = new ControlInput(r.core, { maxPayloadBytes: 20 }, 0);
    expect(input.receive('#001P1600T0100!#001P1600T0100!', 0)).toEqual(['$ERR:payload too large!']);
    expect(input.receive('#00XP!', 0)).toHaveLength(1);
    expect(Object.values(input.counters.rejected)).toEqual([1]);
    expect(r.driver.moves).toEqual([]);
  });
});
