import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { decodeFrame, FRAME_PATTERNS, PWM_MAX, PWM_MIN, SERVO_ID_ALL } from '../src/index.ts';
import { decodeCommonFrame } from '../src/decode.ts';

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
/** `#…P…!` texts near a position report, and position reports with any 3-digit id and pwm. */
const nearMiss = fc
  .tuple(
    fc.array(CHARS, { minLength: 0, maxLength: 4 }),
    fc.array(CHARS, { minLength: 0, maxLength: 7 }),
  )
  .map(([a, b]) => `#${a.join('')}P${b.join('')}!`);
const valid = fc
  .tuple(fc.integer({ min: 0, max: 999 }), fc.integer({ min: 0, max: 99999 }))
  .map(([id, pwm]) => `#${String(id).padStart(3, '0')}P${pwm}!`);

describe('position frames read without the regular expression', () => {
  it('decode exactly as FRAME_PATTERNS.position does, for near-miss texts too', () => {
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

describe("the common shapes read in place (the reader's fast path)", () => {
  const TIM_CHARS = fc.constantFrom('$', 'T', 'I', 'M', ':', '!', '0', '1', '9', 'x', '#', 'P');
  it('give what decodeFrame gives for the same text, or leave it to decodeFrame', () => {
    const nearTime = fc
      .array(TIM_CHARS, { minLength: 0, maxLength: 20 })
      .map((a) => `$TIM:${a.join('')}!`);
    const time = fc
      .tuple(fc.nat({ max: 17 }), fc.bigInt({ min: 0n, max: 10n ** 17n }))
      .map(([zeros, ms]) => `$TIM:${'0'.repeat(zeros)}${ms}!`);
    const other = fc.array(TIM_CHARS, { minLength: 1, maxLength: 12 }).map((a) => a.join(''));
    fc.assert(
      fc.property(
        fc.oneof(nearMiss, valid, nearTime, time, other),
        fc.string({ maxLength: 3 }),
        fc.string({ maxLength: 3 }),
        (text, before, after) => {
          const s = before + text + after;
          const got = decodeCommonFrame(s, before.length, before.length + text.length);
          const want = decodeFrame(text);
          if (got) expect(want).toEqual({ ok: true, frame: got });
          // a valid frame of these shapes always takes the fast path, but a 16-digit stamp
          else if (want.ok && (want.frame.type === 'position' || want.frame.type === 'time'))
            expect(text.length).toBeGreaterThan(21);
        },
      ),
      { numRuns: 4000 },
    );
  });

  it('a stamp of 16 digits and out-of-range reports are left to decodeFrame', () => {
    expect(decodeCommonFrame('$TIM:1780000000000!', 0, 19)).toEqual({
      type: 'time',
      ms: 1780000000000,
    });
    expect(decodeCommonFrame('$TIM:9999999999999999!', 0, 22)).toBeNull();
    expect(decodeCommonFrame('#255P1500!', 0, 10)).toBeNull();
    expect(decodeCommonFrame('#000P1!', 0, 7)).toBeNull();
    expect(decodeCommonFrame('x#001P1500!y', 1, 11)).toEqual({
      type: 'position',
      id: 1,
      pwm: 1500,
    });
  });
});
