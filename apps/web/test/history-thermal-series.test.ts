/**
 * What the History charts draw of the thermal model: a dashed prediction per servo on the
 * grid's times (gaps where it cannot say), the motion's power measured and predicted, and a
 * marker per stored early warning, named for its servo.
 */
import { describe, expect, test } from 'vitest';
import type { AuditRecord, ThermalModelAnswer } from '@armtwin/api';
import { alignSeries } from '../src/ui/panels/History/align.ts';
import {
  powerSeries,
  predictedSeries,
  warningMarkers,
  WARNING_MARKER_COLOUR,
} from '../src/ui/panels/History/thermalSeries.ts';

const names: Record<string, string> = { '000': 'Base', '001': 'Shoulder' };
const name = (id: string) => names[id] ?? id;
const params = { tauS: 20, restC: 30, gainCPerDegS: 0.1, volt0V: 7.4, sagVPerDegS: 0.002 };
const servo = (id: string, temp: (number | null)[]) => ({
  id,
  params,
  fitted: true,
  tauFitted: true,
  intervals: 30,
  r2: 0.9,
  rmseC: 0.3,
  voltRmseV: 0.01,
  reason: '',
  predicted: { temp, volt: temp.map((t) => (t === null ? null : 7.3)) },
});
const ANSWER: ThermalModelAnswer = {
  arm: 'arm1',
  start: 0,
  stop: 3000,
  stepMs: 1000,
  times: [500, 1500, 2500],
  servos: [servo('000', [30, 31, null]), servo('001', [33, 34, 35])],
  power: { supplyOhms: 0.3, measuredW: [0, 2.5, null], predictedW: [0, 2.4, 0.1] },
};

describe('the thermal model in the History charts', () => {
  test('one predicted series per servo, on the grid, with gaps where the model cannot say', () => {
    const s = predictedSeries(ANSWER, 'temp', name);
    expect(s.map((x) => [x.id, x.label])).toEqual([
      ['000', 'predicted Base'],
      ['001', 'predicted Shoulder'],
    ]);
    const a = alignSeries(s);
    expect(a.times).toEqual([500, 1500, 2500]);
    expect(a.columns[0]).toEqual([30, 31, null]);
    expect(predictedSeries(ANSWER, 'volt', name)[1]!.values).toEqual([7.3, 7.3, 7.3]);
  });

  test('power: measured and predicted', () => {
    const a = alignSeries(powerSeries(ANSWER));
    expect(a.labels).toEqual(['measured', 'predicted']);
    expect(a.columns).toEqual([
      [0, 2.5, null],
      [0, 2.4, 0.1],
    ]);
  });

  test('a marker per stored early warning, none for other events', () => {
    const events: AuditRecord[] = [
      { at: 100, by: 'alice', kind: 'taken', detail: '' },
      {
        at: 1200,
        by: 'thermal model',
        kind: 'thermal-warning',
        detail: 'servo 001 heats 2.0 °C/s faster than its model allows',
      },
      { at: 1900, by: 'thermal model', kind: 'thermal-cleared', detail: 'servo 001 heats as…' },
    ];
    expect(warningMarkers(events, name)).toEqual([
      { at: 1200, colour: WARNING_MARKER_COLOUR, label: '⚠ Shoulder' },
    ]);
  });
});
