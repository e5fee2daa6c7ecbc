/**
 * A React box for one history chart: the uPlot instance lives outside React (created when the
 * data changes, resized with the box, destroyed on unmount) and is reported to `historyProbe`.
 * No data → a sentence, never an empty box.
 */
import { useEffect, useRef } from 'react';
import { pointCounts, seriesMax, type Aligned } from './align.ts';
import { createHistoryChart, type ChartSpec } from './historyChart.ts';
import { historyProbe } from './probe.ts';

export function SeriesChart({
  name,
  title,
  aligned,
  spec,
}: {
  /** Key in `historyProbe.charts` and the test id `history-chart-<name>`. */
  name: string;
  /** Accessible description of the chart. */
  title: string;
  aligned: Aligned;
  spec: ChartSpec;
}) {
  const ref = useRef<HTMLDivElement>(null);
  const empty = aligned.times.length === 0;

  useEffect(() => {
    const el = ref.current;
    if (!el || empty) return;
    const chart = createHistoryChart(el, spec, aligned);
    historyProbe.charts[name] = {
      labels: [...aligned.labels],
      points: pointCounts(aligned),
      max: seriesMax(aligned),
      markers: (spec.markers ?? []).map((m) => m.label),
    };
    const ro = new ResizeObserver(() =>
      chart.setSize({ width: Math.max(240, el.clientWidth), height: spec.height }),
    );
    ro.observe(el);
    return () => {
      ro.disconnect();
      chart.destroy();
      delete historyProbe.charts[name];
    };
  }, [aligned, spec, name, empty]);

  if (empty)
    return (
      <p className="dim history-empty" data-testid={`history-chart-${name}`}>
        No data in this range.
      </p>
    );
  return (
    <div
      ref={ref}
      className="history-chart"
      role="img"
      aria-label={title}
      data-testid={`history-chart-${name}`}
    />
  );
}
