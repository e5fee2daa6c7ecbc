/**
 * `healthSummary`: the worst level over the servos' latest reports and its words, the one home
 * of what an arm's summary and the HUD's fleet list say (docs/protocol.md § Fleets).
 */
import { describe, expect, it } from 'vitest';
import { healthSummary } from '../src/index.ts';

describe('healthSummary', () => {
  it('the worst level over the servos, in words', () => {
    expect(healthSummary({ 0: { temp: 30, mv: 7200 }, 1: { temp: 31, mv: 7100 } })).toEqual({
      level: 'normal',
      alarm: '',
    });
    expect(healthSummary({ 0: { temp: 30, mv: 7200 }, 1: { temp: 65, mv: 7100 } })).toEqual({
      level: 'warning',
      alarm: 'servo 001: 65 °C',
    });
    // servo 000's supply below 6.5 V
    expect(healthSummary({ 0: { temp: 30, mv: 6200 }, 1: { temp: 65, mv: 7100 } })).toEqual({
      level: 'critical',
      alarm: 'servo 000: 6.20 V; servo 001: 65 °C',
    });
  });

  it('nothing reported is unknown', () => {
    expect(healthSummary({})).toEqual({ level: 'unknown', alarm: '' });
    expect(healthSummary({ 3: { temp: NaN, mv: NaN } })).toEqual({ level: 'unknown', alarm: '' });
  });
});
