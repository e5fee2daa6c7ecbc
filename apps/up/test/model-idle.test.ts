/** The idle rule that stops a model copy nobody uses (docs/protocol.md § Modes). */
import { describe, expect, test } from 'vitest';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { IdleWatch } from '../src/model-idle.ts';

describe('IdleWatch', () => {
  test('fires once, idleMs after the last touch', () => {
    const clock = new FakeClock();
    let idle = 0;
    new IdleWatch(clock, 10_000, () => idle++);
    clock.advance(9_999);
    expect(idle).toBe(0);
    clock.advance(1);
    expect(idle).toBe(1);
    clock.advance(60_000);
    expect(idle).toBe(1);
  });

  test('activity puts it off; stop() ends it', () => {
    const clock = new FakeClock();
    let idle = 0;
    const w = new IdleWatch(clock, 10_000, () => idle++);
    for (let i = 0; i < 5; i++) {
      clock.advance(6_000);
      w.touch();
    }
    expect(idle).toBe(0);
    clock.advance(10_000);
    expect(idle).toBe(1);
    const w2 = new IdleWatch(clock, 10_000, () => idle++);
    w2.stop();
    clock.advance(20_000);
    expect(idle).toBe(1);
  });
});
