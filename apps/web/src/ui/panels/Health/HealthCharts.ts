/**
 * The temperature and voltage strip charts, outside React: two uPlot charts (one line per
 * servo) redrawn from the store's ring buffers when a new health row has arrived. The
 * temperature chart also draws each servo's predicted temperature (the thermal model,
 * `ArmStore.thermal`) dashed in the servo's colour.
 */
import uPlot from 'uplot';
import { thresholdPlugin, type Threshold } from '../../charts/thresholdPlugin.ts';
import type { ArmStore } from '../../../core/store/ArmStore.ts';
import type { RingBuffer } from '../../../core/store/RingBuffer.ts';
import {
  CHART_HEIGHT,
  CHART_POLL_MS,
  PREDICTED_DASH,
  SERVO_COLOURS,
  TEMP_LINES,
  VOLT_LINES,
} from './constants.ts';

function makeChart(
  el: HTMLElement,
  names: string[],
  unit: string,
  range: [number, number],
  lines: readonly Threshold[],
  dashed = false,
): uPlot {
  const opts: uPlot.Options = {
    width: Math.max(200, el.clientWidth),
    height: CHART_HEIGHT,
    legend: { show: false },
    cursor: { show: false },
    plugins: [thresholdPlugin(lines)],
    scales: {
      x: { time: true },
      y: { range: (_u, min, max) => [Math.min(range[0], min), Math.max(range[1], max)] },
    },
    axes: [
      {
        stroke: '#9ca3af',
        grid: { stroke: '#ffffff14' },
        ticks: { show: false },
        size: 20,
        space: 70,
        incrs: [1, 2, 5, 10, 15, 30, 60, 120, 300, 600],
        font: '10px system-ui',
        values: (_u, vals) => vals.map((v) => clock(v)),
      },
      {
        stroke: '#9ca3af',
        grid: { stroke: '#ffffff14' },
        ticks: { show: false },
        size: 34,
        space: 22,
        font: '10px system-ui',
        values: (_u, vals) => vals.map((v) => `${v}${unit}`),
      },
    ],
    series: [
      {},
      ...names.map((label, i) => ({
        label,
        stroke: SERVO_COLOURS[i % SERVO_COLOURS.length],
        width: 1.5,
        points: { show: false },
      })),
      ...(dashed
        ? names.map((label, i) => ({
            label: `${label} predicted`,
            stroke: SERVO_COLOURS[i % SERVO_COLOURS.length],
            width: 1,
            dash: PREDICTED_DASH,
            points: { show: false },
          }))
        : []),
    ],
  };
  const lineCount = dashed ? names.length * 2 : names.length;
  return new uPlot(opts, [[], ...Array.from({ length: lineCount }, () => [])], el);
}

/** Unix seconds → "hh:mm:ss". */
function clock(s: number): string {
  const d = new Date(s * 1000);
  const p = (n: number) => String(n).padStart(2, '0');
  return `${p(d.getHours())}:${p(d.getMinutes())}:${p(d.getSeconds())}`;
}

function columns(time: RingBuffer, rings: RingBuffer[]): uPlot.AlignedData {
  const n = time.length;
  const x = new Float64Array(n);
  time.copyInto(x);
  return [
    x,
    ...rings.map((r) => {
      const y = new Float64Array(n);
      r.copyInto(y);
      // NaN marks a gap (HealthHistory.pushGap): uPlot breaks a line only at null.
      return Array.from(y, (v) => (Number.isNaN(v) ? null : v));
    }),
  ] as uPlot.AlignedData;
}

export class HealthCharts {
  private readonly temp: uPlot;
  private readonly volt: uPlot;
  private version = -1;
  private readonly timer: ReturnType<typeof setInterval>;
  private readonly resizeObserver: ResizeObserver;

  constructor(
    private readonly store: ArmStore,
    tempEl: HTMLElement,
    voltEl: HTMLElement,
  ) {
    const names = store.opts.arm.servos.map((s) => s.name);
    this.temp = makeChart(tempEl, names, '°', [20, 80], TEMP_LINES, true);
    this.volt = makeChart(voltEl, names, 'V', [6, 8], VOLT_LINES);
    this.timer = setInterval(() => this.update(), CHART_POLL_MS);
    this.resizeObserver = new ResizeObserver(() => {
      this.temp.setSize({ width: Math.max(200, tempEl.clientWidth), height: CHART_HEIGHT });
      this.volt.setSize({ width: Math.max(200, voltEl.clientWidth), height: CHART_HEIGHT });
    });
    this.resizeObserver.observe(tempEl);
  }

  update(): void {
    const h = this.store.history;
    if (h.version === this.version) return;
    this.version = h.version;
    this.temp.setData(columns(h.time, [...h.temp, ...h.predicted]));
    this.volt.setData(columns(h.time, h.volt));
  }

  dispose(): void {
    clearInterval(this.timer);
    this.resizeObserver.disconnect();
    this.temp.destroy();
    this.volt.destroy();
  }
}
