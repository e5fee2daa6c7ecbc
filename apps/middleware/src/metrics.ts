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

/** Every family `/metrics` shows, in the order shown. */
const METRIC_FAMILIES: readonly Family[] = [
  {
    name: 'messages_total',
    type: 'counter',
    help: 'MQTT messages received, by topic kind.',
    label: 'topic',
    values: (m) => m.messages,
  },
  {
    name: 'frames_total',
    type: 'counter',
    help: 'Frames decoded, by kind.',
    label: 'kind',
    values: (m) => m.frames,
  },
  {
    name: 'frames_rejected_total',
    type: 'counter',
    help: 'Input dropped by the cleaner, by reason.',
    label: 'reason',
    values: (m) => m.rejected,
  },
  {
    name: 'points_produced_total',
    type: 'counter',
    help: 'Points made from frames.',
    value: (m) => m.pointsProduced,
  },
  {
    name: 'timestamps_bumped_total',
    type: 'counter',
    help: 'Point times moved forward 1 us to stay unique in their series.',
    value: (m) => m.timestampsBumped,
  },
  {
    name: 'points_written_total',
    type: 'counter',
    help: 'Points InfluxDB accepted.',
    value: (m) => m.pointsWritten,
  },
  {
    name: 'write_batches_total',
    type: 'counter',
    help: 'Write requests, by result.',
    label: 'result',
    values: (m) => m.batches,
  },
  {
    name: 'write_latency_seconds',
    type: 'histogram',
    help: 'InfluxDB write request latency.',
    histogram: (m) => m.writeLatency,
  },
  {
    name: 'write_retries_total',
    type: 'counter',
    help: 'Write attempts that repeated an earlier failed one.',
    value: (m) => m.retries,
  },
  {
    name: 'points_rejected_total',
    type: 'counter',
    help: 'Points InfluxDB refused as bad data (kept in spool/rejected).',
    value: (m) => m.pointsRejected,
  },
  {
    name: 'points_dropped_total',
    type: 'counter',
    help: 'Points lost. Must stay 0.',
    value: (m) => m.pointsDropped,
  },
  {
    name: 'spool_files',
    type: 'gauge',
    help: 'Batches waiting on disk.',
    value: (m) => m.spoolFiles,
  },
  {
    name: 'spool_points',
    type: 'gauge',
    help: 'Points waiting on disk.',
    value: (m) => m.spoolPoints,
  },
  {
    name: 'spool_bytes',
    type: 'gauge',
    help: 'Bytes waiting on disk.',
    value: (m) => m.spoolBytes,
  },
  {
    name: 'spool_other_destination_points',
    type: 'gauge',
    help: 'Points waiting in the spool for another InfluxDB destination (written only by a middleware configured for it).',
    value: (m) => m.spoolOtherPoints,
  },
  {
    name: 'spool_full',
    type: 'gauge',
    help: '1 while the spool is at its bound and MQTT intake is paused.',
    value: (m) => m.spoolFull,
  },
  {
    name: 'spool_full_events_total',
    type: 'counter',
    help: 'Times the spool reached its bound.',
    value: (m) => m.spoolFullEvents,
  },
  {
    name: 'disk_errors_total',
    type: 'counter',
    help: 'Journal or spool file errors.',
    value: (m) => m.diskErrors,
  },
  {
    name: 'mqtt_connected',
    type: 'gauge',
    help: '1 while connected to the broker.',
    value: (m) => m.mqttConnected,
  },
  {
    name: 'mqtt_connects_total',
    type: 'counter',
    help: 'Successful MQTT connections.',
    value: (m) => m.mqttConnects,
  },
  {
    name: 'mqtt_broker',
    type: 'gauge',
    help: "The broker in use: its place in MQTT_URL's list.",
    value: (m) => m.mqttBroker,
  },
  {
    name: 'mqtt_broker_moves_total',
    type: 'counter',
    help: 'Moves to another broker of the list.',
    value: (m) => m.mqttBrokerMoves,
  },
  {
    name: 'influx_reachable',
    type: 'gauge',
    help: '1 while InfluxDB answers.',
    value: (m) => m.influxReachable,
  },
  {
    name: 'storage_enabled',
    type: 'gauge',
    help: '1 when INFLUX_URL is set (or a local influxd runs).',
    value: (m) => m.storageEnabled,
  },
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
