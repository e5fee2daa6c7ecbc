import { describe, expect, it } from 'vitest';
import { breakdownSummary, type StopBreakdown } from '../lib/estop-probe.ts';

const sample = (total: number, dispatch: number, page: number, queue: number, wire: number) =>
  ({ total, input: total - dispatch, dispatch, page, queue, wire }) satisfies StopBreakdown;

describe('breakdownSummary (where the emergency stop’s time went)', () => {
  it('summarises each part and lists the slowest samples whole, slowest first', () => {
    const parts = [
      sample(5, 1, 2, 1.5, 2),
      sample(40, 30, 2, 1.5, 8),
      sample(NaN, NaN, NaN, NaN, NaN), // a stop that never arrived
      sample(12, 1, 1, NaN, 10), // keydown: the HUD's listener came first, no queue figure
    ];
    const s = breakdownSummary(parts, 2) as unknown as {
      total: { n: number; max: number };
      queue: { n: number };
      slowest: StopBreakdown[];
    };
    expect(s.total.n).toBe(3);
    expect(s.total.max).toBe(40);
    expect(s.queue.n).toBe(2);
    expect(s.slowest.map((p) => p.total)).toEqual([40, 12]);
    expect(s.slowest[0]).toMatchObject({ input: 10, dispatch: 30, wire: 8 });
  });
});
