import { describe, expect, test } from 'vitest';
import { alarmEpisodes, detectRuns, sortEpisodes, type Sample } from '../src/history/alarms.ts';

const s = (...pairs: [number, number][]): Sample[] => pairs.map(([t, v]) => ({ t, v }));

describe('temperature episodes', () => {
  test('exactly 60 °C starts a warning, 59.999 does not; exactly 75 °C starts a critical', () => {
    const eps = alarmEpisodes(
      'arm1',
      '001',
      'temp',
      s([0, 59.999], [1, 60], [2, 74.999], [3, 75], [4, 75], [5, 74.9], [6, 59.9]),
    );
    expect(eps).toEqual([
      { kind: 'temp-warning', arm: 'arm1', id: '001', start: 1, end: 6, peak: 75 },
      { kind: 'temp-critical', arm: 'arm1', id: '001', start: 3, end: 5, peak: 75 },
    ]);
  });

  test('an episode still going at the last sample has end null', () => {
    expect(alarmEpisodes('a', '002', 'temp', s([10, 50], [20, 61], [30, 66.5], [40, 63]))).toEqual([
      { kind: 'temp-warning', arm: 'a', id: '002', start: 20, end: null, peak: 66.5 },
    ]);
  });

  test('an episode open at the first sample starts there', () => {
    expect(alarmEpisodes('a', '000', 'temp', s([5, 80], [6, 70], [7, 40]))).toEqual([
      { kind: 'temp-warning', arm: 'a', id: '000', start: 5, end: 7, peak: 80 },
      { kind: 'temp-critical', arm: 'a', id: '000', start: 5, end: 6, peak: 80 },
    ]);
  });

  test('two separate episodes; a drop below the threshold for one sample ends the first', () => {
    const eps = alarmEpisodes(
      'a',
      '003',
      'temp',
      s([0, 60], [1, 62], [2, 59.5], [3, 61], [4, 64], [5, 20]),
    );
    expect(eps.map((e) => [e.start, e.end, e.peak])).toEqual([
      [0, 2, 62],
      [3, 5, 64],
    ]);
  });

  test('no samples, or all normal: no episodes', () => {
    expect(alarmEpisodes('a', '001', 'temp', [])).toEqual([]);
    expect(alarmEpisodes('a', '001', 'temp', s([0, 20], [1, 59.99]))).toEqual([]);
  });
});

describe('undervoltage episodes', () => {
  test('exactly 6.5 V is normal, 6.499 V is low; peak is the lowest voltage', () => {
    expect(
      alarmEpisodes(
        'arm1',
        '004',
        'volt',
        s([0, 6.5], [1, 6.499], [2, 6.1], [3, 6.3], [4, 6.5], [5, 6.2]),
      ),
    ).toEqual([
      { kind: 'undervoltage', arm: 'arm1', id: '004', start: 1, end: 4, peak: 6.1 },
      { kind: 'undervoltage', arm: 'arm1', id: '004', start: 5, end: null, peak: 6.2 },
    ]);
  });

  test('voltage samples never produce temperature episodes and vice versa', () => {
    expect(alarmEpisodes('a', '001', 'volt', s([0, 80]))).toEqual([]);
    expect(alarmEpisodes('a', '001', 'temp', s([0, 5]))).toEqual([]);
  });
});

test('detectRuns keeps the first sample of the worst value', () => {
  expect(
    detectRuns(
      s([0, 1], [1, 3], [2, 3], [3, 0]),
      (v) => v > 0,
      (a, b) => a > b,
    ),
  ).toEqual([{ start: 0, end: 3, peak: 3 }]);
});

test('sortEpisodes orders by start, then id, then kind', () => {
  const e = (
    kind: 'temp-warning' | 'temp-critical' | 'undervoltage',
    id: string,
    start: number,
  ) => ({ kind, arm: 'a', id, start, end: null, peak: 0 });
  const sorted = sortEpisodes([
    e('undervoltage', '001', 5),
    e('temp-critical', '000', 5),
    e('temp-warning', '000', 5),
    e('temp-warning', '002', 1),
  ]);
  expect(sorted.map((x) => `${x.start}/${x.id}/${x.kind}`)).toEqual([
    '1/002/temp-warning',
    '5/000/temp-warning',
    '5/000/temp-critical',
    '5/001/undervoltage',
  ]);
});
