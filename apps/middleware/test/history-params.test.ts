import { describe, expect, test } from 'vitest';
import { parseIds, parseParams, type Endpoint } from '../src/history/params.ts';
import { parseRfc3339, parseTime } from '../src/history/time.ts';

const NOW = Date.UTC(2024, 5, 1, 12, 0, 0);
const DAY = 86_400_000;
const parse = (endpoint: Endpoint, qs: string) =>
  parseParams(endpoint, new URLSearchParams(qs), NOW, 31 * DAY);

/** Values a client could send to break out of a Flux string or expression. */
const HOSTILE = [
  '"',
  'arm1"',
  'arm1") |> drop(columns: ["_value"]) //',
  '") |> drop(',
  'arm1,arm2',
  'arm 1',
  'arm1\n|> yield()',
  'ärm',
  'arm1\u0000',
  '${arm}',
  'ARM1',
  'a'.repeat(33),
  '',
  '\\',
  '🤖',
];

describe('times', () => {
  test.each([
    ['now', NOW],
    ['-5m', NOW - 300_000],
    ['-1h', NOW - 3_600_000],
    ['-24h', NOW - DAY],
    ['-7d', NOW - 7 * DAY],
    ['-2w', NOW - 14 * DAY],
    ['-500ms', NOW - 500],
    ['1700000000123', 1_700_000_000_123],
    ['2023-11-14T22:13:20Z', 1_700_000_000_000],
    ['2023-11-14T22:13:20.123456789Z', 1_700_000_000_123],
    ['2023-11-14T23:13:20.5+01:00', 1_700_000_000_500],
    ['2023-11-14T20:43:20-01:30', 1_700_000_000_000],
  ])('%s', (text, ms) => {
    expect(parseTime(text, NOW)).toBe(ms);
  });

  test.each([
    '',
    '5m',
    '+5m',
    '-5',
    '-5y',
    '- 5m',
    '-1.5h',
    'yesterday',
    '2023-02-30T00:00:00Z',
    '2023-11-14 22:13:20Z',
    '2023-11-14T22:13:20',
    '2023-11-14T24:00:00Z',
    '2023-11-14T22:13:20+25:00',
    '99999999999999999',
    '1e12',
    '-1',
    '2300-01-01T00:00:00Z',
    '0x10',
    ' 1700000000000',
    '1700000000000\n',
    '１７００',
    '-999999999w',
  ])('rejects %j', (text) => {
    expect(parseTime(text, NOW)).toBeUndefined();
  });

  test('parseRfc3339 checks the calendar', () => {
    expect(parseRfc3339('2024-02-29T00:00:00Z')).toBe(Date.UTC(2024, 1, 29));
    expect(parseRfc3339('2023-02-29T00:00:00Z')).toBeUndefined();
  });
});

describe('parseParams', () => {
  test('defaults: every id, the last hour', () => {
    expect(parse('alarms', 'arm=arm1')).toEqual({
      ok: true,
      params: { arm: 'arm1', ids: 'all', field: 'angle', startMs: NOW - 3_600_000, stopMs: NOW },
    });
  });

  test('ids: repeated, comma-separated, deduplicated and sorted', () => {
    const r = parse('series', 'arm=arm-2&field=temp&id=003,001&id=001&start=-5m');
    expect(r).toMatchObject({
      ok: true,
      params: { arm: 'arm-2', ids: ['001', '003'], field: 'temp', startMs: NOW - 300_000 },
    });
    expect(parseIds(['all'])).toBe('all');
    expect(parseIds(['254'])).toEqual(['254']);
  });

  test.each([
    ['series', 'field=temp', 'arm'],
    ['series', 'arm=arm1', 'field'],
    ['series', 'arm=arm1&field=TEMP', 'field'],
    ['series', 'arm=arm1&field=temp,volt', 'field'],
    ['alarms', 'arm=arm1&field=temp', 'field'],
    ['alarms', 'arm=arm1&id=255', 'id'],
    ['alarms', 'arm=arm1&id=1', 'id'],
    ['alarms', 'arm=arm1&id=0001', 'id'],
    ['alarms', 'arm=arm1&id=001,', 'id'],
    ['alarms', 'arm=arm1&id=all,001', 'id'],
    ['alarms', 'arm=arm1&id=', 'id'],
    ['alarms', 'arm=arm1&start=-1h&stop=-2h', 'start'],
    ['alarms', 'arm=arm1&start=now', 'start'],
    ['alarms', 'arm=arm1&start=-32d', 'start'],
    ['alarms', 'arm=arm1&stop=tomorrow', 'stop'],
    ['alarms', 'arm=arm1&arm=arm2', 'arm'],
    ['tracking', 'arm=arm1&bucket=_monitoring', 'bucket'],
    ['pose', 'arm=arm1&start=-1h&start=-2h', 'start'],
  ] as const)('%s?%s → 400 naming %s', (endpoint, qs, parameter) => {
    const r = parse(endpoint, qs);
    expect(r.ok).toBe(false);
    if (!r.ok) {
      expect(r.parameter).toBe(parameter);
      expect(r.error.length).toBeGreaterThan(0);
    }
  });

  test('exactly 31 days is accepted', () => {
    expect(parse('series', 'arm=a&field=volt&start=-31d').ok).toBe(true);
  });

  test.each(HOSTILE)('hostile arm %j is rejected', (arm) => {
    const r = parseParams('series', new URLSearchParams({ arm, field: 'temp' }), NOW, 31 * DAY);
    expect(r).toMatchObject({ ok: false, parameter: 'arm' });
  });

  test.each(HOSTILE)('hostile id, field, start, stop %j are rejected, each named', (v) => {
    for (const parameter of ['id', 'field', 'start', 'stop']) {
      const q = new URLSearchParams({ arm: 'arm1', field: 'temp', [parameter]: v });
      expect(parseParams('series', q, NOW, 31 * DAY)).toMatchObject({ ok: false, parameter });
    }
  });

  test('the error message shows a hostile value as an escaped, bounded JSON string', () => {
    const r = parse('series', `arm=arm1&field=${encodeURIComponent('x"\n' + 'y'.repeat(100))}`);
    expect(r.ok).toBe(false);
    if (!r.ok) {
      expect(r.error).not.toContain('\n');
      expect(r.error).toContain('x\\"\\n');
      expect(r.error.length).toBeLessThan(140);
    }
  });
});
