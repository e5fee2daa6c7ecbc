import { describe, expect, it } from 'vitest';
import { alignSeries, holdUntil, pointCounts } from '../src/ui/panels/History/align.ts';
import {
  alarmsCsv,
  csvCell,
  csvFileName,
  seriesCsv,
  toCsv,
  trackingCsv,
} from '../src/ui/panels/History/csv.ts';

const name = (id: string) => ({ '000': 'Base', '002': 'Elbow' })[id] ?? `servo ${id}`;

describe('CSV cells (RFC 4180, no formulas)', () => {
  it.each([
    [12.5, '12.5'],
    [-3, '-3'],
    [NaN, ''],
    [null, ''],
    [undefined, ''],
    ['plain', 'plain'],
    ['a,b', '"a,b"'],
    ['say "hi"', '"say ""hi"""'],
    ['two\nlines', '"two\nlines"'],
    ['=HYPERLINK("x")', '"\'=HYPERLINK(""x"")"'],
    ['+1', "'+1"],
    ['-1', "'-1"],
    ['@SUM(A1)', "'@SUM(A1)"],
  ] as const)('%j → %s', (v, out) => {
    expect(csvCell(v)).toBe(out);
  });

  it('rows end in CRLF', () => {
    expect(toCsv(['a', 'b'], [[1, 'x']])).toBe('a,b\r\n1,x\r\n');
  });
});

describe('aligned series → one time column, one column per series', () => {
  const aligned = alignSeries([
    { label: 'Base', times: [1000, 2000, 3000], values: [40, 41, 42] },
    { label: 'Elbow', times: [2000, 4000], values: [50, 51] },
  ]);

  it('aligns on the union of the times, null where a series has no point', () => {
    expect(aligned).toEqual({
      labels: ['Base', 'Elbow'],
      times: [1000, 2000, 3000, 4000],
      columns: [
        [40, 41, 42, null],
        [null, 50, null, 51],
      ],
    });
    expect(pointCounts(aligned)).toEqual([3, 2]);
  });

  it('writes epoch ms and UTC ISO times', () => {
    expect(seriesCsv(aligned).split('\r\n')).toEqual([
      'time_ms,time_utc,Base,Elbow',
      '1000,1970-01-01T00:00:01.000Z,40,',
      '2000,1970-01-01T00:00:02.000Z,41,50',
      '3000,1970-01-01T00:00:03.000Z,42,',
      '4000,1970-01-01T00:00:04.000Z,,51',
      '',
    ]);
  });

  it('no series → a header only', () => {
    expect(seriesCsv(alignSeries([]))).toBe('time_ms,time_utc\r\n');
  });
});

describe('tables', () => {
  it('tracking error per joint', () => {
    const csv = trackingCsv(
      [
        { id: '000', samples: 10, meanAbsError: 0.25, maxAbsError: 1.5, maxAt: 5000 },
        { id: '002', samples: 0, meanAbsError: null, maxAbsError: null, maxAt: null },
      ],
      name,
    );
    expect(csv.split('\r\n')).toEqual([
      'id,joint,samples,mean_abs_error_deg,max_abs_error_deg,max_at_utc',
      '000,Base,10,0.25,1.5,1970-01-01T00:00:05.000Z',
      '002,Elbow,0,,,',
      '',
    ]);
  });

  it('alarm log: ongoing episodes have no end', () => {
    const csv = alarmsCsv(
      [
        { kind: 'temp-warning', arm: 'arm1', id: '002', start: 1000, end: 9000, peak: 74.5 },
        { kind: 'undervoltage', arm: 'arm1', id: '000', start: 2000, end: null, peak: 6.1 },
      ],
      name,
    );
    expect(csv.split('\r\n')).toEqual([
      'kind,id,servo,start_utc,end_utc,ongoing,peak',
      'temp-warning,002,Elbow,1970-01-01T00:00:01.000Z,1970-01-01T00:00:09.000Z,no,74.5',
      'undervoltage,000,Base,1970-01-01T00:00:02.000Z,,yes,6.1',
      '',
    ]);
  });

  it('file names are safe', () => {
    expect(csvFileName('arm-1', 'temp', Date.UTC(2024, 4, 1, 10, 2, 3))).toBe(
      'armtwin-arm-1-temp-2024-05-01T100203Z.csv',
    );
    expect(csvFileName('../x', 'a/b', 0)).not.toMatch(/[/\\]/);
  });
});

describe('holdUntil: a command stays drawn while in force', () => {
  it('repeats the last value at the end', () => {
    expect(holdUntil({ label: 'c', times: [10, 20], values: [1, 2] }, 50)).toEqual({
      label: 'c',
      times: [10, 20, 50],
      values: [1, 2, 2],
    });
  });
  it.each([
    [[], [], 50],
    [[10, 50], [1, 2], 50],
    [[10], [1], NaN],
  ])('leaves %j alone (end %d)', (times, values, end) => {
    const s = { label: 'c', times, values };
    expect(holdUntil(s, end)).toBe(s);
  });
});
