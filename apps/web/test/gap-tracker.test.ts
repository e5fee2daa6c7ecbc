import { describe, expect, it } from 'vitest';
import { GapTracker, gapWords } from '../src/core/link/GapTracker.ts';
import { HealthHistory } from '../src/core/store/HealthHistory.ts';

describe('GapTracker', () => {
  it('the first connection is not a gap', () => {
    const g = new GapTracker();
    expect(g.lost(0)).toBe(false); // never connected: connecting failed, no gap
    expect(g.restored(1000)).toBeNull();
    expect(g.view(1000)).toEqual({ kind: 'none' });
  });

  it('a drop shows "disconnected since", then the gap for a while', () => {
    const g = new GapTracker({ showForMs: 30_000 });
    g.restored(0);
    const lostAt = new Date(2024, 0, 1, 12, 34, 56).getTime();
    expect(g.lost(lostAt)).toBe(true);
    expect(g.lost(lostAt + 500)).toBe(false); // close, then offline: one gap
    expect(gapWords(g.view(lostAt + 1000))).toBe(
      'broker disconnected since 12:34:56 — reconnecting',
    );
    expect(g.restored(lostAt + 7400)).toBe(7400);
    expect(gapWords(g.view(lostAt + 8000))).toBe('reconnected; gap of 7.4 s');
    expect(g.view(lostAt + 7400 + 30_000)).toEqual({ kind: 'none' });
    expect(g.gaps).toBe(1);
  });

  it('long gaps in whole seconds', () => {
    const g = new GapTracker();
    g.restored(0);
    g.lost(1000);
    g.restored(43_600);
    expect(gapWords(g.view(43_700))).toBe('reconnected; gap of 43 s');
  });
});

describe('HealthHistory.pushGap', () => {
  it('adds a row of NaN after the last row, so the chart breaks the line there', () => {
    const h = new HealthHistory(2, 8);
    h.push(100, [40, 41], [7.4, 7.3]);
    const v = h.version;
    h.pushGap(99); // the browser clock is behind the arm's: still after the last row
    expect(h.version).toBe(v + 1);
    expect(h.time.latest()).toBeCloseTo(100.001, 6);
    expect(h.temp[0]!.latest()).toBeNaN();
    expect(h.volt[1]!.latest()).toBeNaN();
    h.push(105, [42, 43], [7.4, 7.3]);
    expect(h.temp[0]!.latest()).toBe(42);
  });
});
