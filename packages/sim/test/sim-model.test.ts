import { describe, expect, test } from 'vitest';
import { solveIk } from '@armtwin/ik';
import type { Frame, Group } from '@armtwin/protocol';
import { SimModel } from '../src/model.ts';

const T0 = 1_000_000;
const move = (id: number, pwm: number, ms: number): Frame => ({ type: 'move', id, pwm, ms });
const group = (frames: Frame[], invalid = 0): Group => ({ type: 'group', frames, invalid });

function run(model: SimModel, frame: Frame, t = T0): string[] {
  const out: string[] = [];
  model.execute(frame, t, out);
  return out;
}

describe('SimModel motion', () => {
  test('a feasible move interpolates linearly and arrives at the commanded time', () => {
    const m = new SimModel({}, T0);
    expect(run(m, move(1, 1800, 1000))).toEqual([]);
    expect(m.pwmAt(1, T0)).toBe(1500);
    expect(m.pwmAt(1, T0 + 500)).toBe(1650);
    expect(m.pwmAt(1, T0 + 999)).toBe(1800);
    expect(m.pwmAt(1, T0 + 1000)).toBe(1800);
    expect(m.pwmAt(0, T0 + 1000)).toBe(1500);
  });

  test('a move faster than 60°/0.16 s takes as long as the top speed needs', () => {
    const m = new SimModel({}, T0);
    run(m, move(0, 2500, 0)); // 1000 µs = 135° → 0.36 s at 375°/s
    expect(m.pwmAt(0, T0 + 180)).toBe(2000);
    expect(m.pwmAt(0, T0 + 359)).toBeLessThan(2500);
    expect(m.pwmAt(0, T0 + 360)).toBe(2500);
  });

  test('a new move starts from where the servo is, not where it was going', () => {
    const m = new SimModel({}, T0);
    run(m, move(2, 2000, 1000));
    run(m, move(2, 1500, 250), T0 + 500); // at 1750
    expect(m.pwmAt(2, T0 + 625)).toBe(1625);
    expect(m.pwmAt(2, T0 + 750)).toBe(1500);
  });

  test('#255 moves every servo; PDST stops one where it is; #255PDST! stops all', () => {
    const m = new SimModel({}, T0);
    run(m, move(255, 1700, 1000));
    run(m, { type: 'stop', id: 1 }, T0 + 500);
    expect(m.pwmAt(1, T0 + 2000)).toBe(1600);
    expect(m.pwmAt(0, T0 + 600)).toBe(1620);
    run(m, { type: 'stop', id: 255 }, T0 + 600);
    for (let i = 0; i < 6; i++) expect(m.pwmAt(i, T0 + 5000)).toBe(i === 1 ? 1600 : 1620);
  });
});

describe('SimModel commands', () => {
  test('refuses moves outside a joint limit and unknown servos; nothing moves', () => {
    const m = new SimModel({}, T0);
    expect(run(m, move(5, 1000, 100))).toEqual(['$ERR:limit 005 P1000 outside 1500-2167!']);
    expect(run(m, move(255, 2400, 100))).toEqual(['$ERR:limit 001 P2400 outside 833-2167!']);
    expect(run(m, move(9, 1500, 100))).toEqual(['$ERR:no servo 009!']);
    for (let i = 0; i < 6; i++) expect(m.pwmAt(i, T0 + 1000)).toBe(1500);
  });

  test('groups are all-or-nothing', () => {
    const m = new SimModel({}, T0);
    const out: string[] = [];
    m.executeGroup(group([move(0, 1800, 100), move(5, 1000, 100)]), T0, out);
    m.executeGroup(group([move(0, 1800, 100)], 1), T0, out);
    expect(out).toEqual([
      '$ERR:group rejected: limit 005 P1000 outside 1500-2167!',
      '$ERR:group rejected: 1 bad frame(s)!',
    ]);
    expect(m.pwmAt(0, T0 + 500)).toBe(1500);
    m.executeGroup(group([move(0, 1800, 200), move(1, 1200, 200)]), T0, out);
    expect([m.pwmAt(0, T0 + 100), m.pwmAt(1, T0 + 100)]).toEqual([1650, 1350]);
    expect([m.pwmAt(0, T0 + 200), m.pwmAt(1, T0 + 200)]).toEqual([1800, 1200]);
  });

  test('reads answer position and health; a group of reads answers as a group', () => {
    const m = new SimModel({}, T0);
    expect(run(m, { type: 'readPosition', id: 3 })).toEqual(['#003P1500!']);
    expect(run(m, { type: 'readHealth', id: 1 })[0]).toMatch(/^#001T0\d\dV7\d{3}!$/);
    const out: string[] = [];
    m.executeGroup(
      group([
        { type: 'readPosition', id: 0 },
        { type: 'readPosition', id: 1 },
      ]),
      T0,
      out,
    );
    expect(out).toEqual(['{#000P1500!#001P1500!}']);
    expect(run(m, { type: 'readPosition', id: 255 })[0]).toMatch(/^\{(#00\dP1500!){6}\}$/);
  });

  test('$KMS answers the IK code and moves servos 000–003 only when it is 0', () => {
    const m = new SimModel({}, T0);
    expect(run(m, { type: 'kms', x: 0, y: 0, z: 900, ms: 500 })).toEqual(['$KMS:2!']);
    expect(m.pwmAt(1, T0 + 1000)).toBe(1500);
    const target = solveIk(150, 50, 120);
    expect(target.code).toBe(0);
    expect(run(m, { type: 'kms', x: 150, y: 50, z: 120, ms: 800 })).toEqual(['$KMS:0!']);
    for (let j = 0; j < 4; j++) expect(m.pwmAt(j, T0 + 2000)).toBe(target.pwm[j]);
  });

  test('$PNG is echoed; status frames on control are refused', () => {
    const m = new SimModel({}, T0);
    expect(run(m, { type: 'ping', seq: 4294967295 })).toEqual(['$PNG:4294967295!']);
    expect(run(m, { type: 'position', id: 0, pwm: 1500 })).toEqual([
      '$ERR:unexpected position frame on control!',
    ]);
  });
});

describe('SimModel physics', () => {
  test('moving warms a servo, rest cools it back towards its holding temperature', () => {
    const m = new SimModel({}, T0);
    const rest = m.servos.temp[1]!;
    let t = T0;
    for (let k = 0; k < 60; k++) {
      run(m, move(1, k % 2 ? 833 : 2167, 0), t);
      t += 480; // full range at top speed
      m.advance(t);
    }
    const hot = m.servos.temp[1]!;
    expect(hot).toBeGreaterThan(rest + 10);
    m.advance(t + 120_000);
    expect(m.servos.temp[1]!).toBeLessThan(rest + 1);
  });

  test('a thermal time scale of 4 warms a stalled servo in 5 s as much as real time does in 20 s', () => {
    const warm = (scale: number, ms: number) => {
      const m = new SimModel({ thermalTimeScale: scale }, T0);
      m.servos.setStalled(1, true, T0);
      run(m, move(1, 2000, 0));
      for (let t = T0; t <= T0 + ms; t += 20) m.advance(t);
      return m.servos.temp[1]!;
    };
    const real = warm(1, 20_000);
    expect(real).toBeGreaterThan(warm(1, 0) + 20);
    expect(warm(4, 5_000)).toBeCloseTo(real, 6);
    // The motion is not scaled: a move takes as long as ever.
    const m = new SimModel({ thermalTimeScale: 4 }, T0);
    run(m, move(0, 2000, 1000));
    expect(m.servos.pwmAt(0, T0 + 500)).toBeCloseTo(1750, 6);
  });

  test('several servos moving at once sag the supply below 6.5 V; one does not', () => {
    const m = new SimModel({}, T0);
    run(m, move(0, 2500, 0));
    m.advance(T0 + 100);
    expect(m.servos.mv[0]!).toBeGreaterThan(6500);
    const out: string[] = [];
    m.executeGroup(
      group([move(0, 500, 0), move(2, 2500, 0), move(3, 2000, 0), move(4, 2500, 0)]),
      T0 + 100,
      out,
    );
    m.advance(T0 + 200);
    expect(m.servos.mv[0]!).toBeLessThan(6500);
    m.advance(T0 + 2000);
    expect(m.servos.mv[0]!).toBeGreaterThan(7000);
  });
});
