/**
 * The middleware's counters and their Prometheus text rendering. Plain data: every stage
 * increments its own counters; `/metrics` renders them; the HUD reads the same numbers.
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

function family(out: string[], name: string, type: string, help: string, rows: string[]): void {
  out.push(`# HELP ${name} ${help}`, `# TYPE ${name} ${type}`, ...rows);
}

const labelled = (name: string, label: string, map: Record<string, number>): string[] =>
  Object.entries(map).map(([k, v]) => line(name, v, { [label]: k }));

/** Prometheus text exposition format 0.0.4. */
export function renderMetrics(m: Metrics): string {
  const out: string[] = [];
  const P = 'armtwin_middleware_';
  family(
    out,
    `${P}messages_total`,
    'counter',
    'MQTT messages received, by topic kind.',
    labelled(`${P}messages_total`, 'topic', m.messages),
  );
  family(
    out,
    `${P}frames_total`,
    'counter',
    'Frames decoded, by kind.',
    labelled(`${P}frames_total`, 'kind', m.frames),
  );
  family(
    out,
    `${P}frames_rejected_total`,
    'counter',
    'Input dropped by the cleaner, by reason.',
    labelled(`${P}frames_rejected_total`, 'reason', m.rejected),
  );
  family(out, `${P}points_produced_total`, 'counter', 'Points made from frames.', [
    line(`${P}points_produced_total`, m.pointsProduced),
  ]);
  family(
    out,
    `${P}timestamps_bumped_total`,
    'counter',
    'Point times moved forward 1 us to stay unique in their series.',
    [line(`${P}timestamps_bumped_total`, m.timestampsBumped)],
  );
  family(out, `${P}points_written_total`, 'counter', 'Points InfluxDB accepted.', [
    line(`${P}points_written_total`, m.pointsWritten),
  ]);
  family(
    out,
    `${P}write_batches_total`,
    'counter',
    'Write requests, by result.',
    labelled(`${P}write_batches_total`, 'result', m.batches),
  );
  const h = m.writeLatency;
  const name = `${P}write_latency_seconds`;
  family(out, name, 'histogram', 'InfluxDB write request latency.', [
    ...h.counts.map((c, i) => line(`${name}_bucket`, c, { le: String(LATENCY_BUCKETS[i]) })),
    line(`${name}_bucket`, h.count, { le: '+Inf' }),
    line(`${name}_sum`, h.sum),
    line(`${name}_count`, h.count),
  ]);
  family(
    out,
    `${P}write_retries_total`,
    'counter',
    'Write attempts that repeated an earlier failed one.',
    [line(`${P}write_retries_total`, m.retries)],
  );
  family(
    out,
    `${P}points_rejected_total`,
    'counter',
    'Points InfluxDB refused as bad data (kept in spool/rejected).',
    [line(`${P}points_rejected_total`, m.pointsRejected)],
  );
  family(out, `${P}points_dropped_total`, 'counter', 'Points lost. Must stay 0.', [
    line(`${P}points_dropped_total`, m.pointsDropped),
  ]);
  family(out, `${P}spool_files`, 'gauge', 'Batches waiting on disk.', [
    line(`${P}spool_files`, m.spoolFiles),
  ]);
  family(out, `${P}spool_points`, 'gauge', 'Points waiting on disk.', [
    line(`${P}spool_points`, m.spoolPoints),
  ]);
  family(out, `${P}spool_bytes`, 'gauge', 'Bytes waiting on disk.', [
    line(`${P}spool_bytes`, m.spoolBytes),
  ]);
  family(
    out,
    `${P}spool_other_destination_points`,
    'gauge',
    'Points waiting in the spool for another InfluxDB destination (written only by a middleware configured for it).',
    [line(`${P}spool_other_destination_points`, m.spoolOtherPoints)],
  );
  family(
    out,
    `${P}spool_full`,
    'gauge',
    '1 while the spool is at its bound and MQTT intake is paused.',
    [line(`${P}spool_full`, m.spoolFull ? 1 : 0)],
  );
  family(out, `${P}spool_full_events_total`, 'counter', 'Times the spool reached its bound.', [
    line(`${P}spool_full_events_total`, m.spoolFullEvents),
  ]);
  family(out, `${P}disk_errors_total`, 'counter', 'Journal or spool file errors.', [
    line(`${P}disk_errors_total`, m.diskErrors),
  ]);
  family(out, `${P}mqtt_connected`, 'gauge', '1 while connected to the broker.', [
    line(`${P}mqtt_connected`, m.mqttConnected ? 1 : 0),
  ]);
  family(out, `${P}mqtt_connects_total`, 'counter', 'Successful MQTT connections.', [
    line(`${P}mqtt_connects_total`, m.mqttConnects),
  ]);
  family(out, `${P}mqtt_broker`, 'gauge', "The broker in use: its place in MQTT_URL's list.", [
    line(`${P}mqtt_broker`, m.mqttBroker),
  ]);
  family(out, `${P}mqtt_broker_moves_total`, 'counter', 'Moves to another broker of the list.', [
    line(`${P}mqtt_broker_moves_total`, m.mqttBrokerMoves),
  ]);
  family(out, `${P}influx_reachable`, 'gauge', '1 while InfluxDB answers.', [
    line(`${P}influx_reachable`, m.influxReachable ? 1 : 0),
  ]);
  family(
    out,
    `${P}storage_enabled`,
    'gauge',
    '1 when INFLUX_URL is set (or a local influxd runs).',
    [line(`${P}storage_enabled`, m.storageEnabled ? 1 : 0)],
  );
  return out.join('\n') + '\n';
}
