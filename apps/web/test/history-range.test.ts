import { describe, expect, it } from 'vitest';
import {
  MAX_SPAN_MS,
  parseLocalInput,
  resolveRange,
  toLocalInput,
  type RangeChoice,
} from '../src/ui/panels/History/range.ts';
import { applyQuery, defaultSettings } from '../src/core/config/settings.ts';

const NOW = Date.UTC(2024, 4, 1, 12, 0, 0);
const choice = (c: Partial<RangeChoice>): RangeChoice => ({
  preset: '5m',
  customStart: '',
  customStop: '',
  ...c,
});

describe('History range → start/stop', () => {
  it('an exact custom range (an episode replayed from the list) keeps its milliseconds', () => {
    const start = NOW + 1234;
    const stop = NOW + 61_007;
    const exact = choice({
      preset: 'custom',
      customStart: toLocalInput(start, true),
      customStop: toLocalInput(stop, true),
    });
    expect(resolveRange(exact, NOW)).toEqual({ ok: true, range: { start, stop } });
    expect(toLocalInput(start)).toMatch(/T\d\d:\d\d$/); // to the minute by default
  });

  it.each([
    ['5m', 5 * 60_000],
    ['1h', 3_600_000],
    ['24h', 86_400_000],
  ] as const)('%s ends now and spans %i ms', (preset, ms) => {
    expect(resolveRange(choice({ preset }), NOW)).toEqual({
      ok: true,
      range: { start: NOW - ms, stop: NOW },
    });
  });

  it('custom: two datetime-local values, read as local time', () => {
    const r = resolveRange(
      choice({
        preset: 'custom',
        customStart: '2024-05-01T10:00',
        customStop: '2024-05-01T10:30:15',
      }),
      NOW,
    );
    expect(r).toEqual({
      ok: true,
      range: {
        start: new Date(2024, 4, 1, 10, 0).getTime(),
        stop: new Date(2024, 4, 1, 10, 30, 15).getTime(),
      },
    });
  });

  it.each([
    ['', '2024-05-01T10:00', 'Enter a start date and time.'],
    ['2024-05-01T10:00', 'soon', 'Enter an end date and time.'],
    ['2024-05-01T10:00', '2024-05-01T10:00', 'The start must be before the end.'],
    ['2024-05-01T11:00', '2024-05-01T10:00', 'The start must be before the end.'],
    ['2024-01-01T00:00', '2024-03-01T00:00', 'The range can be at most 31 days.'],
  ])('custom %j – %j is refused: %s', (customStart, customStop, error) => {
    expect(resolveRange(choice({ preset: 'custom', customStart, customStop }), NOW)).toEqual({
      ok: false,
      error,
    });
  });

  it('31 days exactly is allowed', () => {
    const start = new Date(2024, 0, 1).getTime();
    const r = resolveRange(
      choice({
        preset: 'custom',
        customStart: toLocalInput(start),
        customStop: toLocalInput(start + MAX_SPAN_MS),
      }),
      NOW,
    );
    expect(r.ok).toBe(true);
  });

  it('toLocalInput and parseLocalInput round-trip to the minute', () => {
    const t = new Date(2024, 11, 31, 23, 59).getTime();
    expect(toLocalInput(t)).toBe('2024-12-31T23:59');
    expect(parseLocalInput(toLocalInput(t))).toBe(t);
    expect(parseLocalInput('2024-12-31 23:59')).toBeUndefined();
    expect(parseLocalInput('2024-13-40T99:99')).toBeUndefined();
  });
});

describe('the api setting', () => {
  const base = defaultSettings({ protocol: 'https:', host: 'twin.example:8443' });
  it('defaults to /api on the page origin', () => {
    expect(base.apiBase).toBe('https://twin.example:8443/api');
  });
  it.each([
    ['?api=http://127.0.0.1:8090/api/', 'http://127.0.0.1:8090/api'],
    ['?api=/middleware/api', '/middleware/api'],
    ['?api=javascript:alert(1)', 'https://twin.example:8443/api'],
    ['?api=ws://x/api', 'https://twin.example:8443/api'],
  ])('%s → %s', (query, api) => {
    expect(applyQuery(base, query).apiBase).toBe(api);
  });
});
