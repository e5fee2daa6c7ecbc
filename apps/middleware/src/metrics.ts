/**
 * The middleware's counters and their Prometheus text rendering. Plain data: every stage
 * increments its own counters; `/metrics` renders them from one table (`METRIC_FAMILIES`: name,
 * type, help and where the value is read); the HUD reads the same numbers.
 */

/** Upper bounds (seconds) of the write-latency histogram. */
export const LATENCY_BUCKETS = [0.005, 0.01, 0.025, 0.05, 0.1, 0.25, 0.5, 1, 2.5, 5, 10] as const;

export class Histogram {
  readonly counts = new Array<number>(LATENCY_BUCKETS.length).fill(0);
  count = 0;
  sum = 0;
  observe(seconds: number): void {
    this.count++;
    this.sum += seconds;
    for (let i = 0; i < LATENCY_BUCKETS.length; i++) {
      if (seconds <= LATENCY_BUCKETS[i]!) this.counts[i]!++;
    }
  }
}

import type { RecordingCounters } from './cameras/recording-counters.ts';

export class Metrics {
  /** MQTT messages by topic kind (status, control, other). */
  readonly messages: Record<string, number> = {};
  /** Decoded frames by kind (position, health, move, kms, kmsResult, time, …). */
  readonly frames: Record<string, number> = {};
  /** Dropped input by reason (reader error kinds, wrong-direction, bad-topic). */
  readonly rejected: Record<string, number> = {};
  /** Points produced by frames (before any write). */
  pointsProduced = 0;
  /** Timestamps moved forward by 1 µs steps to keep a series' times unique. */
  timestampsBumped = 0;
  pointsWritten = 0;
  /** Write requests by outcome: ok, failed (will retry), rejected (InfluxDB refused the data). */
  readonly batches: Record<string, number> = { ok: 0, failed: 0, rejected: 0 };
  readonly writeLatency = new Histogram();
  retries = 0;
  /** Points InfluxDB refused (4xx: the data's fault); kept in the spool's rejected/ folder. */
  pointsRejected = 0;
  /** Points lost. Must stay 0: nothing in the design drops. */
  pointsDropped = 0;
  /** Times the spool reached its bound (MQTT intake paused). */
  spoolFullEvents = 0;
  spoolFull = false;
  spoolFiles = 0;
  spoolPoints = 0;
  spoolBytes = 0;
  /** Points spooled for another InfluxDB destination (another URL, org or bucket): not ours to write. */
  spoolOtherPoints = 0;
  /** Journal or spool file errors (disk full, permissions). */
  diskErrors = 0;
  mqttConnected = false;
  mqttConnects = 0;
  /** The broker in use: its 1-based place in MQTT_URL's list (0 before the first connection). */
  mqttBroker = 0;
  /** Moves from one broker of the list to another. */
  mqttBrokerMoves = 0;
  influxReachable = false;
  storageEnabled = false;
  /** The camera recording's counters, or null when it is off. */
  cameras: RecordingCounters | null = null;

  count(map: Record<string, number>, key: string, n = 1): void {
    map[key] = (map[key] ?? 0) + n;
  }
}

const line = (name: string, value: number, labels?: Record<string, string>): string => {
  if (!labels) return `${name} ${value}`;
  const l = Object.entries(labels)
    .map(([k, v]) => `${k}="${v.replace(/\\/g, '\\\\').replace(/"/g, '\\"')}"`)
    .join(',');
  return `${name}{${l}} ${value}`;
};

/**
 * One metric family of `/metrics`: its name (after `armtwin_middleware_`), type and help, and
 * its value read from the counters: a number, a boolean (1/0), a map of label value → number
 * (`label` names the label), or the write-latency histogram.
 */
type Family = { name: string; help: string } & (
  | { type: 'counter' | 'gauge'; value: (m: Metrics) => number | boolean }
  | { type: 'counter'; label: string; values: (m: Metrics) => Record<string, number> }
  | { type: 'histogram'; histogram: (m: Metrics) => Histogram }
);

const scalar =
  (type: 'counter' | 'gauge') =>
  (name: string, help: string, value: (m: Metrics) => number | boolean): Family => ({
    name,
    help,
    type,
    value,
  });
const counter = scalar('counter');
const gauge = scalar('gauge');
const labelled = (
  name: string,
  help: string,
  label: string,
  values: (m: Metrics) => Record<string, number>,
): Family => ({ name, help, type: 'counter', label, values });

/** Every family `/metrics` shows, in the order shown. */
const METRIC_FAMILIES: readonly Family[] = [
  labelled('messages_total', 'MQTT messages received, by topic kind.', 'topic', (m) => m.messages),
  labelled('frames_total', 'Frames decoded, by kind.', 'kind', (m) => m.frames),
  labelled(
    'frames_rejected_total',
    'Input dropped by the cleaner, by reason.',
    'reason',
    (m) => m.rejected,
  ),
  counter('points_produced_total', 'Points made from frames.', (m) => m.pointsProduced),
  counter(
    'timestamps_bumped_total',
    'Point times moved forward 1 us to stay unique in their series.',
    (m) => m.timestampsBumped,
  ),
  counter('points_written_total', 'Points InfluxDB accepted.', (m) => m.pointsWritten),
  labelled('write_batches_total', 'Write requests, by result.', 'result', (m) => m.batches),
  {
    name: 'write_latency_seconds',
    type: 'histogram',
    help: 'InfluxDB write request latency.',
    histogram: (m) => m.writeLatency,
  },
  counter(
    'write_retries_total',
    'Write attempts that repeated an earlier failed one.',
    (m) => m.retries,
  ),
  counter(
    'points_rejected_total',
    'Points InfluxDB refused as bad data (kept in spool/rejected).',
    (m) => m.pointsRejected,
  ),
  counter('points_dropped_total', 'Points lost. Must stay 0.', (m) => m.pointsDropped),
  gauge('spool_files', 'Batches waiting on disk.', (m) => m.spoolFiles),
  gauge('spool_points', 'Points waiting on disk.', (m) => m.spoolPoints),
  gauge('spool_bytes', 'Bytes waiting on disk.', (m) => m.spoolBytes),
  gauge(
    'spool_other_destination_points',
    'Points waiting in the spool for another InfluxDB destination (written only by a middleware configured for it).',
    (m) => m.spoolOtherPoints,
  ),
  gauge(
    'spool_full',
    '1 while the spool is at its bound and MQTT intake is paused.',
    (m) => m.spoolFull,
  ),
  counter(
    'spool_full_events_total',
    'Times the spool reached its bound.',
    (m) => m.spoolFullEvents,
  ),
  counter('disk_errors_total', 'Journal or spool file errors.', (m) => m.diskErrors),
  gauge('mqtt_connected', '1 while connected to the broker.', (m) => m.mqttConnected),
  counter('mqtt_connects_total', 'Successful MQTT connections.', (m) => m.mqttConnects),
  gauge('mqtt_broker', "The broker in use: its place in MQTT_URL's list.", (m) => m.mqttBroker),
  counter(
    'mqtt_broker_moves_total',
    'Moves to another broker of the list.',
    (m) => m.mqttBrokerMoves,
  ),
  gauge('influx_reachable', '1 while InfluxDB answers.', (m) => m.influxReachable),
  gauge(
    'storage_enabled',
    '1 when INFLUX_URL is set (or a local influxd runs).',
    (m) => m.storageEnabled,
  ),
  labelled(
    'camera_recording_events_total',
    'Camera recording: connections, takes and why they ended, segments written and deleted (age, size), frames dropped and why, problems.',
    'event',
    (m) => m.cameras?.events ?? {},
  ),
  counter(
    'camera_frames_recorded_total',
    'Camera frames handed to the segmenter.',
    (m) => m.cameras?.frames ?? 0,
  ),
  counter(
    'camera_bytes_recorded_total',
    'H.264 bytes of those frames.',
    (m) => m.cameras?.bytesIn ?? 0,
  ),
  gauge('camera_segments', 'Finished camera segments on disk.', (m) => m.cameras?.segments ?? 0),
  gauge(
    'camera_segment_bytes',
    'Bytes of the finished camera segments on disk.',
    (m) => m.cameras?.bytesStored ?? 0,
  ),
];

function rows(name: string, f: Family, m: Metrics): string[] {
  if ('values' in f)
    return Object.entries(f.values(m)).map(([k, v]) => line(name, v, { [f.label]: k }));
  if ('histogram' in f) {
    const h = f.histogram(m);
    return [
      ...h.counts.map((c, i) => line(`${name}_bucket`, c, { le: String(LATENCY_BUCKETS[i]) })),
      line(`${name}_bucket`, h.count, { le: '+Inf' }),
      line(`${name}_sum`, h.sum),
      line(`${name}_count`, h.count),
    ];
  }
  const v = f.value(m);
  return [line(name, typeof v === 'boolean' ? Number(v) : v)];
}

/** Prometheus text exposition format 0.0.4. */
export function renderMetrics(m: Metrics): string {
  const out: string[] = [];
  for (const f of METRIC_FAMILIES) {
    const name = `armtwin_middleware_${f.name}`;
    out.push(`# HELP ${name} ${f.help}`, `# TYPE ${name} ${f.type}`, ...rows(name, f, m));
  }
  return out.join('\n') + '\n';
}
