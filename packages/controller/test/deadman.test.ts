/**
 * The operator-topic deadman as every driver wires it (`operatorDeadman`, ../src/deadman.ts): a
 * `0` or a lapsed lease asks the driver to stop, and a stop that happened is noted by reason.
 */
import { describe, expect, test } from 'vitest';
import { operatorDeadman } from '../src/mqtt.ts';

/** Timers run by hand: `fire()` runs what is due. */
function manualTimers() {
  const due = new Map<number, () => void>();
  let next = 0;
  return {
    setTimeout: (fn: () => void) => (due.set(++next, fn), next),
    clearTimeout: (h: unknown) => void due.delete(h as number),
    fire: () => {
      for (const [h, fn] of [...due]) {
        due.delete(h);
        fn();
      }
    },
  };
}

describe('operatorDeadman', () => {
  test('a 0 stops a moving arm and says so, by reason', () => {
    const timers = manualTimers();
    const notes: string[] = [];
    let stops = 0;
    const watch = operatorDeadman(
      timers,
      () => (stops++, true),
      (kind) => notes.push(kind),
      100,
    );
    watch.receive('1');
    watch.receive('0');
    expect(stops).toBe(1);
    expect(notes).toEqual(['deadman:released']);
  });

  test('a beating operator that falls silent stops the arm when its lease runs out', () => {
    const timers = manualTimers();
    const notes: string[] = [];
    const watch = operatorDeadman(
      timers,
      () => true,
      (kind) => notes.push(kind),
      100,
    );
    watch.receive('1');
    watch.receive('1'); // beating: the lease runs
    expect(notes).toEqual([]);
    timers.fire();
    expect(notes).toEqual(['deadman:lapsed']);
  });

  test('an arm at rest is not stopped: nothing is noted', () => {
    const notes: string[] = [];
    const watch = operatorDeadman(
      manualTimers(),
      () => false,
      (kind) => notes.push(kind),
    );
    watch.receive('1');
    watch.receive('0');
    expect(notes).toEqual([]);
  });
});
