/**
 * The charts tab: temperature per servo (60 / 75 °C lines), supply voltage per servo (6.5 V
 * line), each with the thermal model's prediction dashed beside it and its early warnings
 * marked; the power the motion drew, measured and predicted; and the chosen joint's actual
 * against commanded angle. Each with its CSV export; a view that failed shows its error text
 * instead.
 */
import { useMemo } from 'react';
import { SERVO_COLOURS, TEMP_LINES, VOLT_LINES } from '../Health/constants.ts';
import { alignSeries, holdUntil, type Aligned } from './align.ts';
import { csvFileName, seriesCsv } from './csv.ts';
import { downloadText } from './download.ts';
import { timeTickFormat, type ChartSpec } from './historyChart.ts';
import type { AngleViews, OverviewViews } from './loadHistory.ts';
import { SeriesChart } from './SeriesChart.tsx';
import type { SeriesAnswer, ThermalModelAnswer } from '@armtwin/api';
import type { Marker } from '../../charts/markerPlugin.ts';
import { powerSeries, predictedSeries, warningMarkers } from './thermalSeries.ts';
import type { Loaded } from './loaded.ts';
import type { ReplayAt } from './historyChart.ts';
import { ViewError, ViewHeader } from './ViewHeader.tsx';

const colourOf = (id: string) => SERVO_COLOURS[Number(id) % SERVO_COLOURS.length]!;
const CHART_HEIGHT = 120;

/** Measured per servo, then the model's prediction per servo (dashed, the same colour). */
function perServo(
  answer: SeriesAnswer,
  name: (id: string) => string,
  model: ThermalModelAnswer | null,
  field: 'temp' | 'volt',
): { aligned: Aligned; ids: string[]; dashed: boolean[] } {
  const measured = answer.series.map((s) => ({
    id: s.id,
    label: name(s.id),
    times: s.times,
    values: s.values,
  }));
  const predicted = model ? predictedSeries(model, field, name) : [];
  const all = [...measured, ...predicted];
  return {
    aligned: alignSeries(all),
    ids: all.map((s) => s.id),
    dashed: all.map((_, i) => i >= measured.length),
  };
}

function ServoSeriesView(props: {
  name: 'temp' | 'volt';
  title: string;
  view: Loaded<SeriesAnswer>;
  spec: Omit<ChartSpec, 'colours' | 'height'>;
  servoName: (id: string) => string;
  arm: string;
  model: ThermalModelAnswer | null;
  markers?: readonly Marker[];
  replayAt: ReplayAt;
}) {
  const { view, servoName, spec, model, markers, name } = props;
  const shown = useMemo(() => {
    if (!view.ok) return null;
    const s = perServo(view.data, servoName, model, name);
    const full: ChartSpec = {
      ...spec,
      colours: s.ids.map(colourOf),
      dashed: s.dashed,
      height: CHART_HEIGHT,
      tick: timeTickFormat(view.data.stop - view.data.start),
      ...(markers ? { markers } : {}),
    };
    return { aligned: s.aligned, spec: full };
  }, [view, servoName, spec, model, markers, name]);
  const csv =
    shown && view.ok
      ? () =>
          downloadText(
            csvFileName(props.arm, props.name, view.data.start),
            seriesCsv(shown.aligned),
          )
      : null;
  return (
    <section className="history-view" aria-label={props.title}>
      <ViewHeader title={props.title} csvLabel={`Download ${props.title} CSV`} onCsv={csv} />
      {!view.ok && <ViewError error={view.error} />}
      {shown && (
        <SeriesChart
          name={props.name}
          title={props.title}
          aligned={shown.aligned}
          spec={shown.spec}
          replayAt={props.replayAt}
        />
      )}
    </section>
  );
}

const TEMP_SPEC = { unit: '°', include: [20, 80], thresholds: TEMP_LINES } as const;
const POWER_COLOURS = ['#38bdf8', '#38bdf8'];
const VOLT_SPEC = { unit: 'V', include: [6, 8], thresholds: VOLT_LINES } as const;
const ANGLE_COLOURS = ['#38bdf8', '#fbbf24'];

export function ChartsView(props: {
  arm: string;
  overview: OverviewViews;
  angles: AngleViews | null;
  servoIds: string[];
  joint: string;
  onJoint: (id: string) => void;
  servoName: (id: string) => string;
  /** The History replay's instant, marked on every chart. */
  replayAt: ReplayAt;
}) {
  const { overview, angles, servoName, replayAt } = props;
  const model = overview.thermal.ok ? overview.thermal.data : null;
  const markers = useMemo(
    () => (overview.audit.ok ? warningMarkers(overview.audit.data.events, servoName) : []),
    [overview.audit, servoName],
  );
  const power = useMemo(() => {
    if (!model) return null;
    const spec: ChartSpec = {
      unit: 'W',
      include: [0, 1],
      colours: POWER_COLOURS,
      dashed: [false, true],
      height: CHART_HEIGHT,
      tick: timeTickFormat(model.stop - model.start),
    };
    return { aligned: alignSeries(powerSeries(model)), spec };
  }, [model]);
  const powerCsv = power
    ? () =>
        downloadText(
          csvFileName(props.arm, 'power', overview.range.start),
          seriesCsv(power.aligned),
        )
    : null;
  const angle = useMemo(() => {
    if (!angles?.actual.ok || !angles.commanded.ok) return null;
    const name = servoName(angles.id);
    const pick = (a: SeriesAnswer) =>
      a.series.find((s) => s.id === angles.id) ?? { times: [], values: [] };
    const actual = pick(angles.actual.data);
    // The command in force is drawn up to the last actual sample (a step, held).
    const commanded = holdUntil(
      { label: `commanded ${name}`, ...pick(angles.commanded.data) },
      actual.times.at(-1) ?? NaN,
    );
    const aligned = alignSeries([{ label: `actual ${name}`, ...actual }, commanded]);
    const spec: ChartSpec = {
      unit: '°',
      colours: ANGLE_COLOURS,
      stepped: [false, true],
      height: CHART_HEIGHT,
      tick: timeTickFormat(angles.range.stop - angles.range.start),
    };
    return { aligned, spec };
  }, [angles, servoName]);
  const angleError =
    angles &&
    (!angles.actual.ok
      ? angles.actual.error
      : !angles.commanded.ok
        ? angles.commanded.error
        : null);
  const angleCsv = angle
    ? () =>
        downloadText(
          csvFileName(props.arm, `angle-${angles!.id}`, overview.range.start),
          seriesCsv(angle.aligned),
        )
    : null;

  return (
    <div className="history-charts">
      <ServoSeriesView
        name="temp"
        title="Temperature"
        view={overview.temp}
        spec={TEMP_SPEC}
        servoName={servoName}
        arm={props.arm}
        model={model}
        markers={markers}
        replayAt={replayAt}
      />
      <ServoSeriesView
        name="volt"
        title="Supply voltage"
        view={overview.volt}
        spec={VOLT_SPEC}
        servoName={servoName}
        arm={props.arm}
        model={model}
        replayAt={replayAt}
      />
      <section className="history-view" aria-label="Power drawn by the motion">
        <ViewHeader
          title="Power drawn by the motion"
          csvLabel="Download power CSV"
          onCsv={powerCsv}
        />
        {!overview.thermal.ok && <ViewError error={overview.thermal.error} />}
        {power && (
          <SeriesChart
            name="power"
            title="Power drawn by the motion, measured and predicted by the thermal model"
            aligned={power.aligned}
            spec={power.spec}
            replayAt={replayAt}
          />
        )}
        {model && (
          <p className="dim small-print" data-testid="thermal-model-note">
            Dashed: the thermal model fitted from this range, from the motion alone (power read from
            the supply&apos;s sag across {model.power.supplyOhms} Ω).
          </p>
        )}
      </section>
      <section className="history-view" aria-label="Commanded and actual angle">
        <ViewHeader
          title="Angle: actual and commanded"
          csvLabel="Download angle CSV"
          onCsv={angleCsv}
        />
        <label className="history-joint">
          Joint{' '}
          <select value={props.joint} onChange={(e) => props.onJoint(e.currentTarget.value)}>
            {props.servoIds.map((id) => (
              <option key={id} value={id}>
                {servoName(id)} ({id})
              </option>
            ))}
          </select>
        </label>
        {angleError && <ViewError error={angleError} />}
        {!angles && <p className="dim">Loading…</p>}
        {angle && (
          <SeriesChart
            name="angle"
            title={`Actual and commanded angle of ${servoName(props.joint)}`}
            aligned={angle.aligned}
            spec={angle.spec}
            replayAt={replayAt}
          />
        )}
      </section>
    </div>
  );
}
