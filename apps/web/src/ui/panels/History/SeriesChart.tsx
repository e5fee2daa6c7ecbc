/**
 * A React box for one history chart: the uPlot instance lives outside React (created when the
 * data changes, resized with the box, destroyed on unmount) and is reported to `historyProbe`.
 * No data → a sentence, never an empty box. The History replay's instant is marked on it (an
 * amber dashed line, redrawn when the replay moves, sampled ten times a second).
 */
import { useEffect, useRef } from 'react';
import { pointCounts, seriesMax, type Aligned } from './align.ts';
import { createHistoryChart, type ChartSpec, type ReplayAt } from './historyChart.ts';
import { historyProbe } from './probe.ts';

const REPLAY_SAMPLE_MS = 100;

export function SeriesChart({
  name,
  title,
  aligned,
  spec,
  replayAt,
}: {
  /** Key in `historyProbe.charts` and the test id `history-chart-<name>`. */
  name: string;
  /** Accessible description of the chart. */
  title: string;
  aligned: Aligned;
  spec: ChartSpec;
  replayAt?: ReplayAt;
}) {
  const ref = useRef<HTMLDivElement>(null);
  const empty = aligned.times.length === 0;

  useEffect(() => {
    const el = ref.current;
    if (!el || empty) return;
    const chart = createHistoryChart(el, spec, aligned, replayAt);
    const probe = (historyProbe.charts[name] = {
      labels: [...aligned.labels],
      points: pointCounts(aligned),
      max: seriesMax(aligned),
      markers: (spec.markers ?? []).map((m) => m.label),
      replayAt: replayAt?.() ?? null,
    });
    const moved = setInterval(() => {
      const at = replayAt?.() ?? null;
      if (at === probe.replayAt) return;
      probe.replayAt = at;
      chart.redraw(false, false);
    }, REPLAY_SAMPLE_MS);
    const ro = new ResizeObserver(() =>
      chart.setSize({ width: Math.max(240, el.clientWidth), height: spec.height }),
    );
    ro.observe(el);
    return () => {
      clearInterval(moved);
      ro.disconnect();
      chart.destroy();
      delete historyProbe.charts[name];
    };
  }, [aligned, spec, name, empty, replayAt]);

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
