import { describe, expect, it } from 'vitest';
import { sampleEqual } from '../src/ui/hud/sampleEqual.ts';

/** What the Health panel samples: one row object per servo, built afresh each time. */
const healthRows = (temp: number) =>
  [0, 1, 2].map((id) => ({
    id,
    name: `servo ${id}`,
    t: id === 2 ? temp : NaN,
    mv: 7400,
    level: 'normal',
    temperatureLevel: 'normal',
    voltageLevel: 'normal',
  }));

describe('sampleEqual (when a sampled panel re-renders)', () => {
  it('an array of row objects built twice from the same state is equal (no re-render)', () => {
    expect(sampleEqual(healthRows(40), healthRows(40))).toBe(true);
  });

  it('a change in any row is not', () => {
    expect(sampleEqual(healthRows(40), healthRows(41))).toBe(false);
    expect(sampleEqual(healthRows(40), healthRows(40).slice(0, 2))).toBe(false);
  });

  it('compares objects and arrays member by member, nested ones too; NaN equals NaN', () => {
    const snap = () => ({ a: 1, b: 'x', c: NaN, list: ['1,2,3'], deep: { rows: [{ v: [1] }] } });
    expect(sampleEqual(snap(), snap())).toBe(true);
    expect(sampleEqual(snap(), { ...snap(), deep: { rows: [{ v: [2] }] } })).toBe(false);
    expect(sampleEqual({ a: 1 }, { a: 1, b: undefined })).toBe(false);
    expect(sampleEqual({ a: 1, b: undefined }, { a: 1, c: undefined })).toBe(false);
    expect(sampleEqual([1, 2], { 0: 1, 1: 2 })).toBe(false);
    expect(sampleEqual('on', 'on')).toBe(true);
    expect(sampleEqual(null, {})).toBe(false);
  });

  it('compares anything but plain data by identity (Maps, typed arrays, class instances)', () => {
    expect(sampleEqual(new Map(), new Map())).toBe(false);
    expect(sampleEqual(new Float64Array(2), new Float64Array(2))).toBe(false);
    const m = new Map([['arm1', 1]]);
    expect(sampleEqual({ fleet: m }, { fleet: m })).toBe(true);
    class Row {
      v = 1;
    }
    expect(sampleEqual([new Row()], [new Row()])).toBe(false);
  });
});
