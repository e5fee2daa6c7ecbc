/**
 * A history chart: one uPlot (outside React) over aligned series, with dashed threshold lines
 * (60 °C / 75 °C, 6.5 V) and a legend. Drawn once per load; the React wrapper recreates it when
 * the data changes and resizes it with its box.
 */
import uPlot from 'uplot';
import { markerPlugin, type Marker } from '../../charts/markerPlugin.ts';
import { thresholdPlugin, type Threshold } from '../../charts/thresholdPlugin.ts';
import type { Aligned } from './align.ts';

export type { Threshold } from '../../charts/thresholdPlugin.ts';

export interface ChartSpec {
  /** Axis unit, e.g. `°C`. */
  unit: string;
  /** The y range always includes this (so thresholds stay in view). */
  include?: readonly [number, number];
  thresholds?: readonly Threshold[];
  /** Colour of each series (by position). */
  colours: readonly string[];
  /** Series drawn as steps with dots (commands) instead of lines, by position. */
  stepped?: readonly boolean[];
  /** Series drawn dashed (a model's prediction), by position. */
  dashed?: readonly boolean[];
  /** Moments marked with a vertical line (the thermal model's early warnings). */
  markers?: readonly Marker[];
  height: number;
  /** Formats an x tick (epoch ms); see `timeTickFormat`. */
  tick?: (ms: number) => string;
}

const p2 = (n: number) => String(n).padStart(2, '0');

/** Tick labels for a range of `spanMs`: HH:MM:SS up to 15 min, HH:MM up to 2 days, else MM-DD HH:MM. */
export function timeTickFormat(spanMs: number): (ms: number) => string {
  return (ms) => {
    const d = new Date(ms);
    const hm = `${p2(d.getHours())}:${p2(d.getMinutes())}`;
    if (spanMs <= 15 * 60_000) return `${hm}:${p2(d.getSeconds())}`;
    if (spanMs <= 2 * 86_400_000) return hm;
    return `${p2(d.getMonth() + 1)}-${p2(d.getDate())} ${hm}`;
  };
}

const AXIS = {
  stroke: '#9ca3af',
  grid: { stroke: '#ffffff14' },
  ticks: { show: false },
  font: '10px system-ui',
};

/** The History replay's instant, epoch ms (null: no replay loaded), marked on every chart. */
export type ReplayAt = () => number | null;
const REPLAY_COLOUR = '#fbbf24';

export function createHistoryChart(
  el: HTMLElement,
  spec: ChartSpec,
  a: Aligned,
  replayAt?: ReplayAt,
): uPlot {
  const replayMarker = (): Marker[] => {
    const at = replayAt?.() ?? null;
    return at === null ? [] : [{ at, colour: REPLAY_COLOUR, label: 'replay' }];
  };
  const include = spec.include;
  const stepped = uPlot.paths.stepped?.({ align: 1 });
  const opts: uPlot.Options = {
    width: Math.max(240, el.clientWidth),
    height: spec.height,
    legend: { show: true, live: false },
    cursor: { drag: { x: false, y: false } },
    plugins: [
      thresholdPlugin(spec.thresholds ?? []),
      markerPlugin(spec.markers ?? []),
      markerPlugin(replayMarker),
    ],
    scales: {
      x: { time: true },
      y: {
        range: (_u, min, max) => {
          const lo = include ? Math.min(include[0], min) : min;
          const hi = include ? Math.max(include[1], max) : max;
          return lo === hi || !Number.isFinite(lo) ? [lo - 1, hi + 1] : [lo, hi];
        },
      },
    },
    axes: [
      {
        ...AXIS,
        size: 22,
        space: 80,
        ...(spec.tick
          ? { values: (_u: uPlot, vals: number[]) => vals.map((v) => spec.tick!(v * 1000)) }
          : {}),
      },
      { ...AXIS, size: 40, space: 24, values: (_u, vals) => vals.map((v) => `${v}${spec.unit}`) },
    ],
    series: [
      {},
      ...a.labels.map((label, i) => ({
        label,
        stroke: spec.colours[i % spec.colours.length],
        width: 1.5,
        spanGaps: true,
        points: { show: Boolean(spec.stepped?.[i]), size: 4 },
        ...(spec.stepped?.[i] && stepped ? { paths: stepped, dash: [4, 3] } : {}),
        ...(spec.dashed?.[i] ? { dash: [4, 3], width: 1.25 } : {}),
      })),
    ],
  };
  const data = [a.times.map((t) => t / 1000), ...a.columns] as uPlot.AlignedData;
  return new uPlot(opts, data, el);
}
