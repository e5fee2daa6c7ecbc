/**
 * The pose a model copy's `POST` asks for (docs/protocol.md § Modes), checked against the arm's
 * servos with every reason named.
 */
import { describe, expect, test } from 'vitest';
import { parseModelPose } from '../src/model-pose.ts';

const SERVOS = [0, 1, 2, 3, 4, 5];

describe('parseModelPose', () => {
  test('no body, or no pulses, is no pose', () => {
    expect(parseModelPose('', SERVOS)).toEqual({ ok: true, pulses: new Map() });
    expect(parseModelPose(' \n', SERVOS)).toEqual({ ok: true, pulses: new Map() });
    expect(parseModelPose('{}', SERVOS)).toEqual({ ok: true, pulses: new Map() });
  });

  test('servo ids as "1" or "001" → pulses by servo id', () => {
    const r = parseModelPose('{"pulses":{"0":1800,"001":1400.5}}', SERVOS);
    expect(r).toEqual({
      ok: true,
      pulses: new Map([
        [0, 1800],
        [1, 1400.5],
      ]),
    });
  });

  test('every problem is named: not JSON, a bad key, a bad value, an unknown field', () => {
    expect(parseModelPose('{nope', SERVOS)).toEqual({
      ok: false,
      errors: ['the request is not JSON'],
    });
    const r = parseModelPose('{"pulses":{"x":1500,"2":"1500","3":null},"speed":1}', SERVOS);
    expect(r.ok).toBe(false);
    const errors = r.ok ? [] : r.errors;
    expect(errors).toEqual(
      expect.arrayContaining([
        expect.stringMatching(/^pulses\.x: a servo id is a number/),
        expect.stringMatching(/^pulses\.2: a pulse width in µs/),
        expect.stringMatching(/^pulses\.3: a pulse width in µs/),
        expect.stringMatching(/"speed"/),
      ]),
    );
    expect(parseModelPose('[1500]', SERVOS).ok).toBe(false);
    expect(parseModelPose('null', SERVOS).ok).toBe(false);
  });

  test('a servo the arm lacks is refused, naming the servos it has', () => {
    expect(parseModelPose('{"pulses":{"1":1500,"9":1500}}', SERVOS)).toEqual({
      ok: false,
      errors: ['pulses.9: the arm has no servo 009 (it has 000, 001, 002, 003, 004, 005)'],
    });
  });
});
