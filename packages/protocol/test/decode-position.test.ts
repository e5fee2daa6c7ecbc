import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { decodeFrame, FRAME_PATTERNS, PWM_MAX, PWM_MIN, SERVO_ID_ALL } from '../src/index.ts';

/** What the regular expression alone says of a position text (the rule before the fast path). */
function byPattern(text: string) {
  const m = FRAME_PATTERNS.position.exec(text);
  if (!m) return null;
  const id = Number(m[1]);
  const pwm = Number(m[2]);
  if (id < 0 || id > SERVO_ID_ALL - 1 || pwm < PWM_MIN || pwm > PWM_MAX) return 'out-of-range';
  return { type: 'position', id, pwm };
}

const CHARS = fc.constantFrom('#', 'P', '!', 'T', 'A', '0', '1', '5', '9', 'x', ' ', '.', '-');

describe('position frames read without the regular expression', () => {
  it('decode exactly as FRAME_PATTERNS.position does, for near-miss texts too', () => {
    const nearMiss = fc
      .tuple(
        fc.array(CHARS, { minLength: 0, maxLength: 4 }),
        fc.array(CHARS, { minLength: 0, maxLength: 7 }),
      )
      .map(([a, b]) => `#${a.join('')}P${b.join('')}!`);
    const valid = fc
      .tuple(fc.integer({ min: 0, max: 999 }), fc.integer({ min: 0, max: 99999 }))
      .map(([id, pwm]) => `#${String(id).padStart(3, '0')}P${pwm}!`);
    fc.assert(
      fc.property(fc.oneof(nearMiss, valid), (text) => {
        const want = byPattern(text);
        const got = decodeFrame(text);
        if (want === null) {
          if (got.ok) expect(got.frame.type).not.toBe('position');
        } else if (want === 'out-of-range') {
          expect(got).toMatchObject({ ok: false, error: { kind: 'out-of-range' } });
        } else expect(got).toEqual({ ok: true, frame: want });
      }),
      { numRuns: 3000 },
    );
  });

  it('leading zeros and the shortest pwm', () => {
    expect(decodeFrame('#007P0600!')).toEqual({
      ok: true,
      frame: { type: 'position', id: 7, pwm: 600 },
    });
    expect(decodeFrame('#000PRAD!')).toEqual({ ok: true, frame: { type: 'readPosition', id: 0 } });
    expect(decodeFrame('#000P1!')).toMatchObject({ ok: false, error: { kind: 'out-of-range' } });
  });
});
