import { InfluxDB, type QueryApi } from '@influxdata/influxdb-client';
import { describe, expect, test } from 'vitest';
import {
  actualCountQuery,
  actualQuery,
  alarmsQuery,
  commandsQuery,
  idClause,
  lastNsBefore,
  poseQuery,
  seriesQuery,
} from '../src/history/queries.ts';
import type { HistoryParams } from '../src/history/params.ts';

const P: HistoryParams = {
  arm: 'arm1',
  ids: ['000', '002'],
  field: 'temp',
  startMs: 1_700_000_000_000,
  stopMs: 1_700_000_300_000,
};

describe('Flux builders', () => {
  test('series: range, filter, mean windows, the exact text', () => {
    expect(String(seriesQuery('armtwin/autogen', P, '200ms'))).toBe(`from(bucket: "armtwin/autogen")
  |> range(start: 2023-11-14T22:13:20.000Z, stop: time(v: "2023-11-14T22:18:19.999999999Z"))
  |> filter(fn: (r) => r._measurement == "servo" and r.arm == "arm1" and (r._field == "temp") and (r.id == "000" or r.id == "002"))
  |> aggregateWindow(every: duration(v: "200ms"), fn: mean, createEmpty: false, timeSrc: "_start")
  |> keep(columns: ["_time", "_value", "id"])`);
  });

  test('every id: no id clause', () => {
    expect(String(idClause('all'))).toBe('');
    expect(String(poseQuery('b', { ...P, ids: 'all' }, '1s'))).not.toContain('r.id');
  });

  test('alarm thresholds are float literals (int vs float would be a Flux type error)', () => {
    const q = String(alarmsQuery('b', P, 100));
    expect(q).toContain('r._value >= 75.0 then 2 else if r._value >= 60.0 then 1');
    expect(q).toContain('r._value < 6.5 then 1');
    expect(q).toContain('limit(n: 101)');
  });

  test('tracking queries: lookback for the command in force, actual from 11 s before start, thinned by window', () => {
    expect(String(commandsQuery('b', P, 86_400_000, 10))).toContain(
      'range(start: 2023-11-13T22:13:20.000Z, stop: time(v: "2023-11-14T22:13:19.999999999Z"))',
    );
    expect(String(actualCountQuery('b', P))).toContain('range(start: 2023-11-14T22:13:09.001Z');
    expect(String(actualQuery('b', P, null))).not.toContain('aggregateWindow(');
    expect(String(actualQuery('b', P, '2s'))).toContain(
      'aggregateWindow(every: duration(v: "2s"), fn: first, createEmpty: false, timeSrc: "_start")',
    );
  });

  /**
   * Defence in depth: even if validation were bypassed, the builders render hostile strings
   * as single escaped Flux string literals.
   */
  test.each(['"', '") |> drop(columns: ["_value"]) //', 'a"b\\', '${x}', 'a\nb', '🤖"'])(
    'hostile %j stays inside one string literal',
    (bad) => {
      const q = String(seriesQuery(bad, { ...P, arm: bad, ids: [bad] }, '1s'));
      const literal = JSON.stringify(bad).replace(/\$\{/g, '\\${');
      expect(q).toContain(`from(bucket: ${literal})`);
      expect(q).toContain(`r.arm == ${literal}`);
      expect(q).toContain(`r.id == ${literal}`);
      // Outside string literals nothing of the hostile value survives.
      const code = q.replace(/"(?:[^"\\]|\\.)*"/g, '""');
      expect(code).not.toContain('drop(');
      expect(code).not.toContain('${');
    },
  );

  test('builders return ParameterizedQuery accepted by a real QueryApi', () => {
    const api: QueryApi = new InfluxDB({ url: 'http://127.0.0.1:9' }).getQueryApi('');
    expect(() => api.response(seriesQuery('b', P, '1s'))).not.toThrow();
  });
});

test('lastNsBefore: the nanosecond before a millisecond instant', () => {
  expect(lastNsBefore(1_700_000_000_000)).toBe('2023-11-14T22:13:19.999999999Z');
  expect(lastNsBefore(1_700_000_000_001)).toBe('2023-11-14T22:13:20.000999999Z');
});
