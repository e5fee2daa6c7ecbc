import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import {
  createReader,
  decodeFrame,
  encodeFrame,
  encodeAngle,
  encodeAngleMove,
  encodeMove,
  encodePosition,
  MAX_FRAME_LENGTH,
  type Frame,
} from '../src/index.ts';

const FRAME_START = fc.constantFrom('#', '$', '{', '}', '!', 'P', 'T', 'V', ':', ',', '0', '1', '9');
const NOISY = fc.array(fc.oneof(fc.string({ maxLength: 80 }), fc.array(FRAME_START, { maxLength: 80 }).map((a) => a.join(''))), {
  maxLength: 30,
});

describe('reader properties', () => {
  it('random bytes never throw and never grow the buffer past its bound', () => {
    fc.assert(
      fc.property(fc.array(fc.uint8Array({ maxLength: 300 }), { maxLength: 20 }), (chunks) => {
        const reader = createReader({});
        for (const chunk of chunks) {
          reader.feed(chunk);
          expect(reader.bufferedBytes).toBeLessThan(MAX_FRAME_LENGTH);
        }
        reader.flush();
        expect(reader.bufferedBytes).toBe(0);
      }),
      { numRuns: 500 },
    );
  });

  it('frame-like noise never throws, never grows the buffer, and every error has a kind', () => {
    fc.assert(
      fc.property(NOISY, (chunks) => {
        const reader = createReader({ onError: (e) => expect(e.kind).toBeTypeOf('string') });
        for (const chunk of chunks) {
          reader.feed(chunk);
          expect(reader.bufferedBytes).toBeLessThan(MAX_FRAME_LENGTH);
        }
      }),
      { numRuns: 500 },
    );
  });

  it('valid frames survive any junk around them and any chunking', () => {
    const move = fc.record({ id: fc.integer({ min: 0, max: 255 }), pwm: fc.integer({ min: 500, max: 2500 }), ms: fc.integer({ min: 0, max: 9999 }) });
    const junk = fc.stringMatching(/^[a-zA-Z0-9 %&*]{0,10}$/);
    fc.assert(
      fc.property(fc.array(fc.tuple(junk, move), { minLength: 1, maxLength: 20 }), fc.array(fc.nat(), { maxLength: 10 }), (items, cuts) => {
        const text = items.map(([j, m]) => j + encodeMove(m.id, m.pwm, m.ms)).join('');
        const got: Frame[] = [];
        const reader = createReader({ onFrame: (f) => got.push(f) });
        const points = [...new Set(cuts.map((c) => c % (text.length + 1)))].sort((a, b) => a - b);
        let at = 0;
        for (const p of [...points, text.length]) {
          reader.feed(text.slice(at, p));
          at = p;
        }
        expect(got).toEqual(items.map(([, m]) => ({ type: 'move', ...m })));
      }),
      { numRuns: 300 },
    );
  });

  it('decodeFrame(encodeFrame(f)) is f for valid positions', () => {
    fc.assert(
      fc.property(fc.integer({ min: 0, max: 254 }), fc.integer({ min: 500, max: 2500 }), (id, pwm) => {
        expect(decodeFrame(encodePosition(id, pwm))).toEqual({ ok: true, frame: { type: 'position', id, pwm } });
        expect(encodeFrame({ type: 'position', id, pwm })).toBe(encodePosition(id, pwm));
      }),
    );
  });

  it('angle frames beside pulse frames survive any junk around them and any chunking', () => {
    const frame = fc.oneof(
      fc.record({ type: fc.constant('angle' as const), id: fc.integer({ min: 0, max: 254 }), deg: fc.integer({ min: -99_999, max: 99_999 }).map((h) => h / 100 + 0) }),
      fc.record({ type: fc.constant('angleMove' as const), id: fc.integer({ min: 0, max: 255 }), deg: fc.integer({ min: -99_999, max: 99_999 }).map((h) => h / 100 + 0), ms: fc.integer({ min: 0, max: 9999 }) }),
      fc.record({ type: fc.constant('position' as const), id: fc.integer({ min: 0, max: 254 }), pwm: fc.integer({ min: 500, max: 2500 }) }),
    );
    const junk = fc.stringMatching(/^[a-zA-Z0-9 %&*]{0,10}$/);
    fc.assert(
      fc.property(fc.array(fc.tuple(junk, frame), { minLength: 1, maxLength: 20 }), fc.array(fc.nat(), { maxLength: 10 }), (items, cuts) => {
        const text = items.map(([j, f]) => j + encodeFrame(f)).join('');
        const got: Frame[] = [];
        const reader = createReader({ onFrame: (f) => got.push(f) });
        const points = [...new Set(cuts.map((c) => c % (text.length + 1)))].sort((a, b) => a - b);
        let at = 0;
        for (const p of [...points, text.length]) {
          reader.feed(text.slice(at, p));
          at = p;
        }
        expect(got).toEqual(items.map(([, f]) => f));
      }),
      { numRuns: 300 },
    );
  });

  it('decodeFrame(encodeFrame(f)) is f for valid angle reports and moves', () => {
    fc.assert(
      fc.property(fc.integer({ min: 0, max: 254 }), fc.integer({ min: -99_999, max: 99_999 }), fc.integer({ min: 0, max: 9999 }), (id, h, ms) => {
        const deg = h / 100 + 0;
        expect(decodeFrame(encodeAngle(id, deg))).toEqual({ ok: true, frame: { type: 'angle', id, deg } });
        expect(decodeFrame(encodeAngleMove(id, deg, ms))).toEqual({ ok: true, frame: { type: 'angleMove', id, deg, ms } });
      }),
    );
  });

  it('decodeFrame never throws on any string', () => {
    fc.assert(fc.property(fc.string({ maxLength: 100 }), (s) => void decodeFrame(s)));
  });
});
