import { describe, expect, it } from 'vitest';
import {
  decodeFrame,
  encodeControllerError,
  encodeFrame,
  encodeGroup,
  encodeHealth,
  encodeKms,
  encodeMove,
  encodePosition,
  EMERGENCY_STOP,
  ProtocolError,
  type Frame,
} from '../src/index.ts';

const FRAMES: [string, Frame][] = [
  ['#001P0900T0250!', { type: 'move', id: 1, pwm: 900, ms: 250 }],
  ['#255PDST!', { type: 'stop', id: 255 }],
  ['#004PRAD!', { type: 'readPosition', id: 4 }],
  ['#004PRTV!', { type: 'readHealth', id: 4 }],
  ['$KMS:-12.5,180,40,-90,800!', { type: 'kms', x: -12.5, y: 180, z: 40, alpha: -90, ms: 800 }],
  ['$KMS:150,0,80,1000!', { type: 'kms', x: 150, y: 0, z: 80, ms: 1000 }],
  ['$PNG:0!', { type: 'ping', seq: 0 }],
  ['#000P2500!', { type: 'position', id: 0, pwm: 2500 }],
  ['#001T045V7400!', { type: 'health', id: 1, temp: 45, mv: 7400 }],
  // A 12 V bus supply: five digits from 10 V up (docs/protocol.md).
  ['#001T036V12000!', { type: 'health', id: 1, temp: 36, mv: 12000 }],
  ['$KMS:2!', { type: 'kmsResult', code: 2 }],
  ['$TIM:1700000000000!', { type: 'time', ms: 1700000000000 }],
  ['$ERR:limit 001!', { type: 'controllerError', text: 'limit 001' }],
];

describe('frame codec', () => {
  it.each(FRAMES)('%s decodes and re-encodes byte for byte', (text, frame) => {
    expect(decodeFrame(text)).toEqual({ ok: true, frame });
    expect(encodeFrame(frame)).toBe(text);
  });

  it('the emergency stop is #255PDST!', () => {
    expect(EMERGENCY_STOP).toBe('#255PDST!');
    expect(decodeFrame(EMERGENCY_STOP)).toEqual({ ok: true, frame: { type: 'stop', id: 255 } });
  });

  it('zero-pads fixed-width fields and groups frames', () => {
    expect(encodeGroup([encodeMove(0, 1500, 1000), encodeMove(1, 900, 5)])).toBe(
      '{#000P1500T1000!#001P0900T0005!}',
    );
    expect(encodeHealth(2, 7.4, 612.6)).toBe('#002T007V0613!');
  });

  it('writes $KMS numbers without exponents or trailing zeros', () => {
    expect(encodeKms(1e-7, -0.0001, 120.25, 0, 45.5)).toBe('$KMS:0,0,120.25,45.5,0!');
  });

  it.each([
    () => encodeMove(0, 499, 100),
    () => encodeMove(0, 2501, 100),
    () => encodeMove(256, 1500, 100),
    () => encodeMove(0, 1500, 10000),
    () => encodeMove(0, 1500.5, 100),
    () => encodePosition(255, 1500),
    () => encodeKms(Number.NaN, 0, 0, 100),
    () => encodeKms(0, 0, 0, 100, 181),
    () => encodeHealth(1, 36, 65_536),
  ])('encoder #%# rejects out-of-range input with a ProtocolError', (encode) => {
    expect(encode).toThrow(ProtocolError);
  });

  it('a supply above 65 535 mV is out of range, not malformed', () => {
    expect(decodeFrame('#001T036V65536!')).toMatchObject({
      ok: false,
      error: { kind: 'out-of-range' },
    });
    expect(decodeFrame('#001T036V65535!')).toMatchObject({ ok: true, frame: { mv: 65_535 } });
  });

  it('a controller error text can never break framing', () => {
    const frame = encodeControllerError('bad #001P! {x} $y\n' + 'z'.repeat(100));
    expect(frame.length).toBeLessThanOrEqual(64);
    expect(frame.slice(5, -1)).not.toMatch(/[!#${}\n]/);
    expect(decodeFrame(frame).ok).toBe(true);
  });
});
