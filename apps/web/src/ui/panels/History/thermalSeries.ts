/**
 * The thermal model in the History charts: what `/history/thermal-model` predicted for the range
 * (each servo's temperature and supply voltage, the power the motion drew) as series to draw
 * dashed beside the measured ones, and the model's stored early warnings (`audit` events of kind
 * `thermal-warning`, docs/protocol.md § A thermal model of each servo) as markers. Pure.
 */
import type { AuditRecord, ThermalModelAnswer } from '@armtwin/api';
import type { Marker } from '../../charts/markerPlugin.ts';
import type { TimeSeries } from './align.ts';

/** Colour of an early-warning marker (the 60 °C line's orange). */
export const WARNING_MARKER_COLOUR = '#f97316';

const values = (list: readonly (number | null)[]): number[] => list.map((v) => v ?? NaN);

/** One dashed series per servo: `predicted <name>`, on the grid's times. */
export function predictedSeries(
  answer: ThermalModelAnswer,
  field: 'temp' | 'volt',
  servoName: (id: string) => string,
): (TimeSeries & { id: string })[] {
  return answer.servos.map((s) => ({
    id: s.id,
    label: `predicted ${servoName(s.id)}`,
    times: answer.times,
    values: values(s.predicted[field]),
  }));
}

/** The motion's power: measured (from the reported voltages) and predicted (the model's). */
export function powerSeries(answer: ThermalModelAnswer): TimeSeries[] {
  return [
    { label: 'measured', times: answer.times, values: values(answer.power.measuredW) },
    { label: 'predicted', times: answer.times, values: values(answer.power.predictedW) },
  ];
}

/** The model's early warnings in range, as chart markers labelled with the servo's name. */
export function warningMarkers(
  events: readonly AuditRecord[],
  servoName: (id: string) => string,
): Marker[] {
  return events
    .filter((e) => e.kind === 'thermal-warning')
    .map((e) => {
      const id = /servo (\d{3})/.exec(e.detail)?.[1];
      return {
        at: e.at,
        colour: WARNING_MARKER_COLOUR,
        label: `⚠ ${id ? servoName(id) : 'warning'}`,
      };
    });
}
