import { describe, expect, it } from 'vitest';
import { OwnEchoes } from '../src/core/link/OwnEchoes.ts';

const enc = (s: string) => new TextEncoder().encode(s);

describe('OwnEchoes', () => {
  it('matches each message sent with one echo, by topic and bytes', () => {
    const e = new OwnEchoes();
    e.note('arm/a/control', '#002P1600T0100!', 0);
    e.note('arm/a/control', '#002P1600T0100!', 10);
    expect(e.take('arm/a/control', enc('#002P1700T0100!'), 20)).toBe(false);
    expect(e.take('arm/b/control', enc('#002P1600T0100!'), 20)).toBe(false);
    expect(e.take('arm/a/control', enc('#002P1600T0100!'), 900)).toBe(true);
    expect(e.take('arm/a/control', '#002P1600T0100!', 900)).toBe(true);
    expect(e.take('arm/a/control', enc('#002P1600T0100!'), 900)).toBe(false);
  });

  it('forgets what never came back, and keeps at most `max`', () => {
    const e = new OwnEchoes(1000, 3);
    e.note('t', 'a', 0);
    expect(e.take('t', 'a', 1001)).toBe(false);
    for (const p of ['1', '2', '3', '4']) e.note('t', p, 2000);
    expect(e.pending).toBe(3);
    expect(e.take('t', '1', 2000)).toBe(false);
    expect(e.take('t', '4', 2000)).toBe(true);
  });
});
