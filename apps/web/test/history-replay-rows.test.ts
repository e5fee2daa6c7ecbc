import { describe, expect, it } from 'vitest';
import { rowsByTime } from '../src/core/replay/rowAt.ts';
import { scrollTopShowing } from '../src/ui/panels/History/keepInView.ts';

describe('rowsByTime: the History table row at the replay instant', () => {
  // A control log: events in time order, two in the same millisecond.
  const log = rowsByTime([1000, 2000, 2000, 3500]);

  it('is the last row at or before the instant', () => {
    expect(log(1000)).toBe(0);
    expect(log(1999)).toBe(0);
    expect(log(3499)).toBe(2);
    expect(log(3500)).toBe(3);
    expect(log(9e12)).toBe(3);
  });

  it('is none before the first row, and with no instant', () => {
    expect(log(999)).toBe(-1);
    expect(log(null)).toBe(-1);
    expect(log(NaN)).toBe(-1);
    expect(rowsByTime([])(5000)).toBe(-1);
  });

  it('takes the later row of the table among rows with the same time', () => {
    expect(log(2000)).toBe(2);
    expect(rowsByTime([7, 7, 7])(7)).toBe(2);
  });

  it('finds rows that are not in time order, and skips rows without a time', () => {
    // The tracking table: one row per joint at its worst moment; joint 1 never compared.
    const worst = rowsByTime([5000, null, 1200, 3000, NaN]);
    expect(worst(1100)).toBe(-1);
    expect(worst(1200)).toBe(2);
    expect(worst(4999)).toBe(3);
    expect(worst(5000)).toBe(0);
    expect(worst(1e13)).toBe(0);
  });
});

describe('scrollTopShowing: the marked row kept in its table box', () => {
  // A box 100 px high scrolled to 200: it shows content 200…300.
  it('leaves the box alone while the row is shown whole', () => {
    expect(scrollTopShowing(200, 100, { top: 200, height: 20 })).toBeNull();
    expect(scrollTopShowing(200, 100, { top: 280, height: 20 })).toBeNull();
  });

  it('brings a row above the view to the top, one below to the bottom', () => {
    expect(scrollTopShowing(200, 100, { top: 150, height: 20 })).toBe(150);
    expect(scrollTopShowing(200, 100, { top: 195, height: 20 })).toBe(195);
    expect(scrollTopShowing(200, 100, { top: 290, height: 20 })).toBe(210);
    expect(scrollTopShowing(200, 100, { top: 900, height: 20 })).toBe(820);
  });

  it('shows the top of a row taller than the box', () => {
    expect(scrollTopShowing(200, 100, { top: 400, height: 150 })).toBe(400);
  });
});
