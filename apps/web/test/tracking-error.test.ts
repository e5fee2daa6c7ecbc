import { describe, expect, it } from 'vitest';
import {
  DEFAULT_TRACKING_PAINT_OPTIONS as O,
  TrackingErrors,
  trackingColour,
  trackingLevel,
} from '../src/core/store/trackingError.ts';
import { ArmStore } from '../src/core/store/ArmStore.ts';

const EPOCH = 1_700_000_000_000;
const state = (pwm: number[]) => `{${pwm.map((p, i) => `#00${i}P${p}!`).join('')}}`;

describe('tracking error ramp', () => {
  it('is ok below okDeg, warn up to errorDeg, error from there; nothing without a command', () => {
    expect(trackingLevel(NaN)).toBe('none');
    expect(trackingLevel(0)).toBe('ok');
    expect(trackingLevel(O.okDeg)).toBe('warn');
    expect(trackingLevel(O.errorDeg)).toBe('error');
    expect(trackingColour(NaN)).toBe(-1);
    expect(trackingColour(0)).toBe(O.colours.ok);
    expect(trackingColour(O.okDeg)).toBe(O.colours.warn);
    expect(trackingColour(O.errorDeg + 10)).toBe(O.colours.error);
  });

  it('paints only once something was commanded, unless switched', () => {
    const t = new TrackingErrors(2);
    expect(t.active).toBe(false);
    t.set(0, NaN, 10);
    expect(t.active).toBe(false);
    t.setting = 'on';
    expect(t.active).toBe(true);
    t.setting = 'auto';
    expect(t.set(1, 20, 10)).toBe(true);
    expect(t.active).toBe(true);
    expect(t.levels).toEqual(['none', 'error']);
    t.setting = 'off';
    expect(t.active).toBe(false);
  });
});

describe('ArmStore tracking error', () => {
  it('reads ~0 for a joint moving as commanded and grows for a stalled one', () => {
    const s = new ArmStore();
    const rest = [1500, 1500, 1500, 1500, 1500, 1500];
    s.ingest(`$TIM:${EPOCH}!${state(rest)}`, 0);
    // Both servos 000 and 001 commanded +400 µs (54°) over 1000 ms.
    s.noteControl('{#000P1900T1000!#001P1900T1000!}', 0);
    for (let k = 1; k <= 25; k++) {
      const moving = 1500 + Math.round(8 * k);
      const stalled = 1500 + Math.round(8 * Math.min(k, 5)); // jammed after 100 ms
      s.ingest(
        `$TIM:${EPOCH + 20 * k}!${state([moving, stalled, 1500, 1500, 1500, 1500])}`,
        20 * k,
      );
      s.sample(20 * k + 1);
    }
    expect(s.tracking.levels[0]).toBe('ok');
    expect(s.tracking.errorDeg[0]).toBeLessThan(0.5);
    expect(s.tracking.levels[1]).toBe('error');
    expect(s.tracking.errorDeg[1]).toBeGreaterThan(O.errorDeg);
    expect(s.tracking.levels[2]).toBe('none');
  });
});
