import { describe, expect, it } from 'vitest';
import { changedOnly } from '../src/ui/hud/changedOnly.ts';

/** What a panel samples: fresh objects each time, equal when the store has not moved. */
const sample = (temp: number) => [{ id: 0, t: temp, mv: NaN }];

describe('changedOnly (useSampled: unchanged samples never reach React)', () => {
  it('hands on nothing while the sampled value stays the same, however long', () => {
    const handed: unknown[] = [];
    const offer = changedOnly(sample(40), (v) => handed.push(v));
    // An hour of a panel whose value never changes, at 4 samples a second.
    for (let i = 0; i < 4 * 3600; i++) offer(sample(40));
    expect(handed).toEqual([]);
  });

  it('hands on each change once, compared with the last value handed on', () => {
    const handed: ReturnType<typeof sample>[] = [];
    const offer = changedOnly(sample(40), (v) => handed.push(v));
    offer(sample(41));
    offer(sample(41));
    offer(sample(40));
    offer(sample(40));
    expect(handed.map((h) => h[0]!.t)).toEqual([41, 40]);
  });
});
