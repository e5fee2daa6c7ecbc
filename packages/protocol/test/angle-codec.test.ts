import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  ANGLE_DEG_MAX,
  decodeFrame,
  encodeAngle,
  encodeAngleMove,
  encodeFrame,
  FRAME_TOPICS,
  ProtocolError,
  type Frame,
} from '../src/index.ts';

const FRAMES: [string, Frame][] = [
  ['#003A-012.50!', { type: 'angle', id: 3, deg: -12.5 }],
  ['#004A+350.00!', { type: 'angle', id: 4, deg: 350 }],
  ['#000A+000.00!', { type: 'angle', id: 0, deg: 0 }],
  ['#254A-999.99!', { type: 'angle', id: 254, deg: -999.99 }],
  ['#001A+270.00T1000!', { type: 'angleMove', id: 1, deg: 270, ms: 1000 }],
  ['#255A-360.00T9999!', { type: 'angleMove', id: 255, deg: -360, ms: 9999 }],
  ['#002A+999.99T0000!', { type: 'angleMove', id: 2, deg: 999.99, ms: 0 }],
];

describe('angle frames (PROTOCOL §8)', () => {
  it.each(FRAMES)('%s decodes and re-encodes byte for byte', (text, frame) => {
    expect(decodeFrame(text)).toEqual({ ok: true, frame });
    expect(encodeFrame(frame)).toBe(text);
  });

  it('travel on their topics: reports on status, moves on control', () => {
    expect(FRAME_TOPICS.angle).toEqual({ control: false, status: true });
    expect(FRAME_TOPICS.angleMove).toEqual({ control: true, status: false });
  });

  it('round to two decimals, half away from zero; minus zero is written +000.00', () => {
    expect(encodeAngle(1, 12.345)).toBe('#001A+012.35!');
    expect(encodeAngle(1, -12.345)).toBe('#001A-012.35!');
    expect(encodeAngle(1, 0.125)).toBe('#001A+000.13!');
    expect(encodeAngle(1, -0.004)).toBe('#001A+000.00!');
    expect(encodeAngle(1, -0)).toBe('#001A+000.00!');
    expect(encodeAngle(1, 349.999999999)).toBe('#001A+350.00!');
    expect(encodeAngleMove(7, 999.994, 5)).toBe('#007A+999.99T0005!');
  });

  it.each([
    () => encodeAngle(1, 999.995), // rounds to 1000.00
    () => encodeAngle(1, -1000),
    () => encodeAngle(1, Number.NaN),
    () => encodeAngle(1, Number.POSITIVE_INFINITY),
    () => encodeAngle(255, 0), // a report comes from one servo
    () => encodeAngleMove(256, 0, 100),
    () => encodeAngleMove(1, 0, 10000),
    () => encodeAngleMove(1, 0, 1.5),
  ])('refuses out-of-range values (%#)', (encode) => {
    expect(encode).toThrow(ProtocolError);
  });

  it('any finite angle in range is written within 0.005° of itself, in 13 bytes', () => {
    fc.assert(
      fc.property(fc.double({ min: -ANGLE_DEG_MAX, max: ANGLE_DEG_MAX, noNaN: true }), (deg) => {
        const text = encodeAngle(4, deg);
        expect(text).toMatch(/^#004A[+-]\d{3}\.\d{2}!$/);
        const back = decodeFrame(text);
        expect(back.ok).toBe(true);
        if (back.ok && back.frame.type === 'angle')
          expect(Math.abs(back.frame.deg - deg)).toBeLessThanOrEqual(0.005 + 1e-9);
      }),
      { numRuns: 500 },
    );
  });
});
