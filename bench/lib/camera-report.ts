/**
 * The camera bench's report (../camera.ts): the windows' figures as table rows beside the
 * issue's target and anchors, the latency histogram (SVG) and the JSON record.
 */
import type { CameraKind } from '@armtwin/camera/announcement';
import type { CameraProbeCamera } from './camera-probe.ts';
import { round, type Summary } from './stats.ts';
import { barChartSvg } from './svg.ts';
import { fmt, type Row } from './types.ts';

/** The paths measured, in order. */
export const KINDS: readonly CameraKind[] = ['mjpeg', 'h264-ws'];
export const NAMES: Record<CameraKind, string> = { mjpeg: 'MJPEG', 'h264-ws': 'H.264/WebCodecs' };
/** Issue 15's loopback target, and the anchors it names. */
export const TARGET = { p50: 80, p99: 150 };
export const ANCHORS =
  'Transitive WebRTC 150–180 ms; Reachy 2 88 ms (glass to glass, with a camera)';

/** What one measurement window gives (../camera.ts `runWindow`). */
export interface CameraWindow {
  kind: CameraKind | null;
  cameras: number;
  fps: number;
  renderedPerS: number;
  busy: number;
  scriptShare: number;
  readerShare: number;
  readerMaxMs: number;
  longTasks: number;
  longestTaskMs: number;
  rafMaxGapMs: number;
  latency: Summary;
  /** Age of the picture shown at every page frame, all views. */
  age: Summary;
  perCamera: (Omit<CameraProbeCamera, 'latency' | 'age'> & {
    latency: Summary;
    age: Summary;
    shownPerS: number;
  })[];
  server: { node: number; ffmpeg: number }[];
  raw: number[];
}

const pct = (v: number) => `${fmt(v * 100, 1)} %`;
const lat = (s: Summary) => `${fmt(s.p50, 0)} / ${fmt(s.p99, 0)} ms`;
const meets = (s: Summary) => s.p50 <= TARGET.p50 && s.p99 <= TARGET.p99;

/** The table rows: per path, one camera and two, against the windows without a camera. */
export function cameraRows(w: Record<string, CameraWindow>): Row[] {
  const none = w.none!;
  const out: Row[] = [];
  for (const kind of KINDS) {
    const one = w[`${kind}-1`]!;
    const two = w[`${kind}-2`]!;
    const still = w[`${kind}-still`]!;
    out.push({
      figure: `Glass to glass, ${NAMES[kind]}, one camera, 640×480 @ 30 fps, loopback, 3D view running (p50 / p99)`,
      value: `${lat(one.latency)} (${one.latency.n} frames)`,
      baseline: `3D view still, camera in the panel only: ${lat(still.latency)} (busy ${pct(still.busy)}); anchors: ${ANCHORS}`,
      target: `p50 ≤ ${TARGET.p50} ms, p99 ≤ ${TARGET.p99} ms`,
      met: meets(one.latency),
    });
    out.push({
      figure: `${NAMES[kind]}, one camera: age of the picture shown at every page frame (p50 / p99; a held or frozen picture keeps ageing)`,
      value: lat(one.age),
      baseline: `3D view still: ${lat(still.age)}`,
      target: 'reported',
      met: null,
    });
    out.push({
      figure: `Glass to glass, ${NAMES[kind]}, two cameras at once (p50 / p99, both views)`,
      value: `${lat(two.latency)} (${two.latency.n} frames)`,
      baseline: `one camera ${lat(one.latency)}`,
      target: `p50 ≤ ${TARGET.p50} ms, p99 ≤ ${TARGET.p99} ms`,
      met: meets(two.latency),
    });
    const s = one.server[0]!;
    out.push({
      figure: `Camera server CPU per ${NAMES[kind]} stream (share of one core: node + ffmpeg)`,
      value: `${pct(s.node + s.ffmpeg)} (node ${pct(s.node)}, ffmpeg ${pct(s.ffmpeg)})`,
      baseline: `two streams: ${two.server.map((x) => pct(x.node + x.ffmpeg)).join(', ')}`,
      target: 'reported',
      met: null,
    });
    out.push({
      figure: `Page with ${NAMES[kind]}: frames/s (rAF; 3D rendered); camera frames shown/s per view`,
      value: `1 cam ${fmt(one.fps, 1)} (${fmt(one.renderedPerS, 1)}), ${one.perCamera.map((c) => fmt(c.shownPerS, 1)).join('')}; 2 cams ${fmt(two.fps, 1)} (${fmt(two.renderedPerS, 1)}), ${two.perCamera.map((c) => fmt(c.shownPerS, 1)).join(' + ')}`,
      baseline: `no camera ${fmt(none.fps, 1)} (${fmt(none.renderedPerS, 1)})`,
      target: 'reported',
      met: null,
    });
    out.push({
      figure: `Page with ${NAMES[kind]}: main-thread busy (CDP TaskDuration); of it the probe's pixel reading`,
      value: `1 cam ${pct(one.busy)} (probe ${pct(one.readerShare)}); 2 cams ${pct(two.busy)} (probe ${pct(two.readerShare)})`,
      baseline: `no camera ${pct(none.busy)}`,
      target: 'reported',
      met: null,
    });
  }
  return out;
}

/**
 * Histogram of the one-camera glass-to-glass latency of both paths, with the 3D view drawing and
 * still, % of frames per bin.
 */
export function latencySvg(w: Record<string, CameraWindow>, title: string): string {
  const bins = 30;
  const hi = Math.max(60, ...KINDS.map((k) => w[`${k}-1`]!.latency.p99 * 1.25));
  const hist = (xs: number[]) => {
    const c = new Array<number>(bins).fill(0);
    for (const v of xs) if (v >= 0) c[Math.min(bins - 1, Math.floor((v / hi) * bins))]!++;
    return c.map((x) => round((100 * x) / Math.max(1, xs.length), 2));
  };
  return barChartSvg({
    title,
    xLabel: 'ms (bin start; last bin: more)',
    yLabel: '% of frames',
    categories: Array.from({ length: bins }, (_, i) => ((i * hi) / bins).toFixed(0)),
    labelEvery: 2,
    series: [
      { name: 'MJPEG, 3D view drawing', values: hist(w['mjpeg-1']!.raw), colour: '#1b9e77' },
      { name: 'H.264, 3D view drawing', values: hist(w['h264-ws-1']!.raw), colour: '#d95f02' },
      { name: 'MJPEG, 3D view still', values: hist(w['mjpeg-still']!.raw), colour: '#a6dba0' },
      { name: 'H.264, 3D view still', values: hist(w['h264-ws-still']!.raw), colour: '#fdb863' },
    ],
  });
}

/** The windows for the JSON: rounded, without the raw samples. */
export function windowsJson(w: Record<string, CameraWindow>): Record<string, unknown> {
  return Object.fromEntries(
    Object.entries(w).map(([k, v]) => {
      const { raw: _raw, ...rest } = v;
      return [
        k,
        {
          ...rest,
          fps: round(v.fps, 2),
          renderedPerS: round(v.renderedPerS, 2),
          busy: round(v.busy, 4),
          scriptShare: round(v.scriptShare, 4),
          readerShare: round(v.readerShare, 4),
          readerMaxMs: round(v.readerMaxMs, 2),
          server: v.server.map((s) => ({ node: round(s.node, 4), ffmpeg: round(s.ffmpeg, 4) })),
        },
      ];
    }),
  );
}
