/**
 * Putting a running sim at a pose (`SimRunner.placeAt`, what a model copy set to the real arm's
 * pose uses): the servos are there at once and at rest, the others stop where they are, a pulse
 * beyond a servo's limits is held at the limit, and an unknown servo changes nothing.
 */
import { describe, expect, test } from 'vitest';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { SimRunner } from '../src/runner.ts';

function harness() {
  const clock = new FakeClock();
  const runner = new SimRunner({ send: () => {} }, clock, {});
  return { clock, runner, model: runner.model };
}

describe('SimRunner.placeAt', () => {
  test('named servos are at the pose at once and at rest; a move under way stops', () => {
    const { clock, runner, model } = harness();
    runner.receive('#000P2000T2000!');
    clock.advance(500);
    const t = clock.now();
    const placed = runner.placeAt(new Map([[1, 1700]]));
    expect(placed).toEqual(new Map([[1, 1700]]));
    expect(model.pwmAt(1, t)).toBe(1700);
    const base = model.pwmAt(0, t);
    expect(base).toBeGreaterThan(1500);
    expect(base).toBeLessThan(2000);
    clock.advance(1000);
    expect(model.pwmAt(0, clock.now())).toBe(base);
    expect(model.pwmAt(1, clock.now())).toBe(1700);
    for (let i = 0; i < model.servos.count; i++)
      expect(model.servos.isMoving(i, clock.now())).toBe(false);
  });

  test("a pulse beyond a servo's limits is held at the limit", () => {
    const { clock, runner, model } = harness();
    const { minPwm } = model.servos;
    const placed = runner.placeAt(new Map([[5, 600]])); // the gripper opens 0..90°
    expect(placed.get(5)).toBe(minPwm[5]);
    expect(model.pwmAt(5, clock.now())).toBe(Math.round(minPwm[5]!));
  });

  test('an unknown servo or a pulse that is not a number changes nothing', () => {
    const { clock, runner, model } = harness();
    expect(() =>
      runner.placeAt(
        new Map([
          [1, 1700],
          [9, 1500],
        ]),
      ),
    ).toThrow('no servo 009');
    expect(() => runner.placeAt(new Map([[1, Number.NaN]]))).toThrow(/not a pulse/);
    expect(model.pwmAt(1, clock.now())).toBe(1500);
  });
});
