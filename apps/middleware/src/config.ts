/**
 * The middleware's settings, read from the environment here and nowhere else.
 * `DEFAULT_MIDDLEWARE_CONFIG` is the one copy of the defaults; the README quotes it.
 */
import { z } from 'zod';
import { MAX_PAYLOAD_BYTES, MQTT_KEEPALIVE_S, MQTT_RECONNECT_MS } from '@armtwin/protocol';
import { parseBrokerList } from '@armtwin/link';
import { QUERY_LANGUAGES, type InfluxSource, type QueryLanguage } from './history/reader.ts';

/** Every setting, with the environment variable it comes from. */
export interface MiddlewareConfig {
  /**
   * MQTT_URL: broker URL (mqtt://, mqtts://, ws://, wss://), or an ordered comma-separated list:
   * the first preferred, the rest fall-backs (docs/protocol.md § Several brokers).
   */
  mqttUrl: string;
  /** MQTT_USERNAME / MQTT_PASSWORD: broker credentials (empty = anonymous). */
  mqttUsername: string;
  mqttPassword: string;
  /** MQTT_CLIENT_ID: fixed, so the broker keeps this instance's persistent session. */
  mqttClientId: string;
  /** MQTT_QOS: subscription QoS, 0 or 1 (1 = nothing lost across a restart). */
  mqttQos: 0 | 1;
  /** MQTT_KEEPALIVE_S: keep-alive interval, seconds. */
  mqttKeepaliveS: number;
  /** MQTT_RECONNECT_MS: reconnect period, ms. */
  mqttReconnectMs: number;
  /** MQTT_SHARE_GROUP: '' = plain subscription; else `$share/<group>/arm/+/…`. */
  mqttShareGroup: string;
  /**
   * NATS_URL: '' = take the stream in over MQTT (above). Else a NATS cluster's servers
   * (`nats://host:4222`, comma-separated): the stream is taken from the JetStream stream where the
   * cluster's MQTT keeps every QoS 1 message, through one durable pull consumer that every
   * middleware of the cluster shares (./nats-intake.ts, docs/cluster.md); MQTT is not used.
   */
  natsUrl: string;
  /** NATS_CONSUMER: the durable consumer's name; the same for every middleware that shares the stream. */
  natsConsumer: string;
  /** NATS_ACK_WAIT_MS: a message a middleware took and did not acknowledge is delivered again after this long. */
  natsAckWaitMs: number;
  /** INFLUX_URL: '' = run without storage. */
  influxUrl: string;
  /** INFLUX_TOKEN: 2.x API token, or `user:password` on 1.8 ('' = no auth). */
  influxToken: string;
  /** INFLUX_ORG: 2.x organisation ('' on 1.8). */
  influxOrg: string;
  /** INFLUX_BUCKET: 2.x bucket, or `db/rp` on 1.8. */
  influxBucket: string;
  /** INFLUX_CREATE_BUCKET: create the database/bucket when missing. */
  influxCreateBucket: boolean;
  /**
   * INFLUX_QUERY_LANGUAGE: what the history API and the export speak. `influxql` (the v1 `/query`
   * API) is served by InfluxDB 1.8, 2.x and 3.x; `flux` by 1.8 (flux-enabled) and 2.x only.
   */
  influxQueryLanguage: QueryLanguage;
  /** WRITE_CONCURRENCY: spool batches written to InfluxDB at once (oldest first). */
  writeConcurrency: number;
  /**
   * WRITE_GZIP: gzip each write's body (`Content-Encoding: gzip`); `auto` = only when InfluxDB is
   * not on this machine (a loopback INFLUX_URL), where it saves no bandwidth and costs CPU.
   */
  writeGzip: 'auto' | boolean;
  /** WRITE_GZIP_LEVEL: zlib level of that gzip, 1 (fastest) to 9 (smallest). */
  writeGzipLevel: number;
  /** BATCH_SIZE: points per write. */
  batchSize: number;
  /** FLUSH_INTERVAL_MS: the longest a point waits before it is written. */
  flushIntervalMs: number;
  /** MAX_RETRY_DELAY_MS: cap of the exponential retry back-off. */
  maxRetryDelayMs: number;
  /** MIN_RETRY_DELAY_MS: first retry delay. */
  minRetryDelayMs: number;
  /** WRITE_MODE: `batch` (default) or `sync` (one write per frame: the seed's baseline). */
  writeMode: 'batch' | 'sync';
  /** SPOOL_DIR: where unwritten batches are kept on disk. */
  spoolDir: string;
  /** SPOOL_MAX_BYTES: bound of the spool; at the bound MQTT intake pauses (loudly). */
  spoolMaxBytes: number;
  /** PORT: HTTP port of /healthz and /metrics (0 = any free port). */
  port: number;
  /** HOST: HTTP bind address. */
  host: string;
  /**
   * API_TOKEN: when set, /metrics and /history need `Authorization: Bearer <token>`; /healthz
   * stays open (it says only up or down). Required outside the local demo (SECURITY.md).
   */
  apiToken: string;
  /**
   * ARMTWIN_USERS: the users-and-roles file (SECURITY.md). With it `/whoami` tells the HUD its
   * role, and a user's name and password (HTTP Basic) also open /metrics and /history, which
   * then need a log-in even without API_TOKEN. Failed log-ins are throttled.
   */
  usersFile: string;
  /**
   * MODELS_DIR: the folder of robot folders (`<dir>/<name>/profile.json`) the HTTP API writes
   * calibrations, keep-out zones and imported robots into, and the MCAP export reads; '' = the
   * repository's `public/models`. Give it the folder the arms' controllers (`armtwin sim
   * --models`, `armtwin gateway --bus --models`) and the HUD's `/models/` read.
   */
  modelsDir: string;
  /** MAX_PAYLOAD_BYTES: a bigger MQTT message is refused whole (counted as `oversize`). */
  maxPayloadBytes: number;
  /**
   * THERMAL_WATCH: run the thermal model's watch over every arm's status stream and publish and
   * store its early warnings (`arm/{id}/alert`, docs/protocol.md § A thermal model of each
   * servo). Needs storage (the models are fitted from it); off with a share group or NATS intake
   * (each instance would see only part of a stream).
   */
  thermalWatch: boolean;
  /** THERMAL_REFIT_MS: how often each arm's thermal models are refitted from its history, ms. */
  thermalRefitMs: number;
  /**
   * FOXGLOVE_PORT: the live Foxglove WebSocket server's port (docs/foxglove.md), on HOST, as
   * `armtwin up --foxglove` serves it; 'off' (unset) = none, 0 = any free port. Beyond loopback
   * only with ARMTWIN_USERS; a user's commands go to the broker under their own log-in.
   */
  foxglovePort: number | 'off';
  /**
   * CAMERA_RECORD: record every announced camera's H.264 stream (docs/cameras-recording.md).
   * Off with a share group or NATS_URL (each instance would record every camera).
   */
  cameraRecord: boolean;
  /** CAMERA_DIR: the recordings' folder (`<dir>/<arm>/<camera>/<startMs>-<endMs>.mp4`). */
  cameraDir: string;
  /** CAMERA_SEGMENT_S: target length of one segment, s (cut at the next key frame). */
  cameraSegmentS: number;
  /** CAMERA_RETENTION_HOURS: segments that ended longer ago are deleted (0 = kept). */
  cameraRetentionHours: number;
  /** CAMERA_RETENTION_BYTES: the folder's bound; the oldest segments go first (0 = none). */
  cameraRetentionBytes: number;
  /** FFMPEG: the ffmpeg program the recording runs. */
  ffmpeg: string;
  /** LOG_LEVEL: pino level. */
  logLevel: 'fatal' | 'error' | 'warn' | 'info' | 'debug' | 'trace' | 'silent';
}

export const DEFAULT_MIDDLEWARE_CONFIG: MiddlewareConfig = {
  mqttUrl: 'mqtt://127.0.0.1:1883',
  mqttUsername: '',
  mqttPassword: '',
  mqttClientId: 'armtwin-middleware',
  mqttQos: 1,
  mqttKeepaliveS: MQTT_KEEPALIVE_S,
  mqttReconnectMs: MQTT_RECONNECT_MS,
  mqttShareGroup: '',
  natsUrl: '',
  natsConsumer: 'armtwin-middleware',
  natsAckWaitMs: 30_000,
  influxUrl: '',
  influxToken: '',
  influxOrg: '',
  influxBucket: 'armtwin/autogen',
  influxCreateBucket: true,
  influxQueryLanguage: 'influxql',
  writeConcurrency: 4,
  writeGzip: 'auto',
  writeGzipLevel: 1,
  batchSize: 1000,
  flushIntervalMs: 5000,
  maxRetryDelayMs: 15000,
  minRetryDelayMs: 500,
  writeMode: 'batch',
  spoolDir: '.data/middleware-spool',
  spoolMaxBytes: 256 * 1024 * 1024,
  port: 8090,
  host: '127.0.0.1',
  apiToken: '',
  usersFile: '',
  modelsDir: '',
  maxPayloadBytes: MAX_PAYLOAD_BYTES,
  thermalWatch: true,
  thermalRefitMs: 5 * 60_000,
  foxglovePort: 'off',
  cameraRecord: true,
  cameraDir: '.data/cameras',
  cameraSegmentS: 10,
  cameraRetentionHours: 24,
  cameraRetentionBytes: 4 * 1024 ** 3,
  ffmpeg: 'ffmpeg',
  logLevel: 'info',
};

/** Config key → environment variable. */
export const CONFIG_ENV: Record<keyof MiddlewareConfig, string> = {
  mqttUrl: 'MQTT_URL',
  mqttUsername: 'MQTT_USERNAME',
  mqttPassword: 'MQTT_PASSWORD',
  mqttClientId: 'MQTT_CLIENT_ID',
  mqttQos: 'MQTT_QOS',
  mqttKeepaliveS: 'MQTT_KEEPALIVE_S',
  mqttReconnectMs: 'MQTT_RECONNECT_MS',
  mqttShareGroup: 'MQTT_SHARE_GROUP',
  natsUrl: 'NATS_URL',
  natsConsumer: 'NATS_CONSUMER',
  natsAckWaitMs: 'NATS_ACK_WAIT_MS',
  influxUrl: 'INFLUX_URL',
  influxToken: 'INFLUX_TOKEN',
  influxOrg: 'INFLUX_ORG',
  influxBucket: 'INFLUX_BUCKET',
  influxCreateBucket: 'INFLUX_CREATE_BUCKET',
  influxQueryLanguage: 'INFLUX_QUERY_LANGUAGE',
  writeConcurrency: 'WRITE_CONCURRENCY',
  writeGzip: 'WRITE_GZIP',
  writeGzipLevel: 'WRITE_GZIP_LEVEL',
  batchSize: 'BATCH_SIZE',
  flushIntervalMs: 'FLUSH_INTERVAL_MS',
  maxRetryDelayMs: 'MAX_RETRY_DELAY_MS',
  minRetryDelayMs: 'MIN_RETRY_DELAY_MS',
  writeMode: 'WRITE_MODE',
  spoolDir: 'SPOOL_DIR',
  spoolMaxBytes: 'SPOOL_MAX_BYTES',
  port: 'PORT',
  host: 'HOST',
  apiToken: 'API_TOKEN',
  usersFile: 'ARMTWIN_USERS',
  modelsDir: 'MODELS_DIR',
  maxPayloadBytes: 'MAX_PAYLOAD_BYTES',
  thermalWatch: 'THERMAL_WATCH',
  thermalRefitMs: 'THERMAL_REFIT_MS',
  foxglovePort: 'FOXGLOVE_PORT',
  cameraRecord: 'CAMERA_RECORD',
  cameraDir: 'CAMERA_DIR',
  cameraSegmentS: 'CAMERA_SEGMENT_S',
  cameraRetentionHours: 'CAMERA_RETENTION_HOURS',
  cameraRetentionBytes: 'CAMERA_RETENTION_BYTES',
  ffmpeg: 'FFMPEG',
  logLevel: 'LOG_LEVEL',
};

const int = (min: number, max: number) => z.coerce.number().int().min(min).max(max);
const url = (protocols: RegExp) =>
  z.string().refine(
    (s) => {
      try {
        return protocols.test(new URL(s).protocol);
      } catch {
        return false;
      }
    },
    `expected a URL (${protocols.source.replace(/[\^$()]/g, '').replace(/\\/g, '')})`,
  );

const SCHEMA = z.object({
  mqttUrl: z.string().superRefine((s, ctx) => {
    try {
      parseBrokerList(s);
    } catch (err) {
      ctx.addIssue({ code: 'custom', message: (err as Error).message });
    }
  }),
  mqttUsername: z.string(),
  mqttPassword: z.string(),
  mqttClientId: z.string().min(1).max(128),
  mqttQos: z.enum(['0', '1']).transform((q) => Number(q) as 0 | 1),
  mqttKeepaliveS: int(0, 65535),
  mqttReconnectMs: int(10, 3_600_000),
  mqttShareGroup: z.string().regex(/^[^/+#]*$/, 'must not contain "/", "+" or "#"'),
  natsUrl: z.union([
    z.literal(''),
    z
      .string()
      .transform((s) => s.split(',').map((u) => u.trim()))
      .pipe(
        z
          .array(url(/^(nats|tls):$/))
          .min(1)
          .max(16),
      )
      .transform((list) => list.join(',')),
  ]),
  natsConsumer: z
    .string()
    .regex(/^[A-Za-z0-9_-]{1,64}$/, 'letters, digits, "_" or "-" (at most 64)'),
  natsAckWaitMs: int(1000, 3_600_000),
  influxUrl: z.union([z.literal(''), url(/^https?:$/)]),
  influxToken: z.string(),
  influxOrg: z.string(),
  influxBucket: z.string().min(1),
  influxCreateBucket: z
    .enum(['true', 'false', '1', '0'])
    .transform((b) => b === 'true' || b === '1'),
  influxQueryLanguage: z.enum(QUERY_LANGUAGES),
  writeConcurrency: int(1, 64),
  writeGzip: z
    .enum(['auto', 'true', 'false', '1', '0'])
    .transform((b) => (b === 'auto' ? b : b === 'true' || b === '1')),
  writeGzipLevel: int(1, 9),
  batchSize: int(1, 1_000_000),
  flushIntervalMs: int(1, 3_600_000),
  maxRetryDelayMs: int(1, 3_600_000),
  minRetryDelayMs: int(1, 3_600_000),
  writeMode: z.enum(['batch', 'sync']),
  spoolDir: z.string().min(1),
  spoolMaxBytes: int(1024, Number.MAX_SAFE_INTEGER),
  port: int(0, 65535),
  host: z.string().min(1),
  apiToken: z.string().regex(/^[\x21-\x7e]*$/, 'printable ASCII, no spaces'),
  usersFile: z.string(),
  modelsDir: z.string(),
  maxPayloadBytes: int(64, 268_435_455),
  thermalWatch: z.enum(['true', 'false', '1', '0']).transform((b) => b === 'true' || b === '1'),
  thermalRefitMs: int(1000, 86_400_000),
  foxglovePort: z.union([z.literal('off'), int(0, 65535)]),
  cameraRecord: z.enum(['true', 'false', '1', '0']).transform((b) => b === 'true' || b === '1'),
  cameraDir: z.string().min(1),
  cameraSegmentS: int(1, 3600),
  cameraRetentionHours: z.coerce
    .number()
    .min(0)
    .max(24 * 3650),
  cameraRetentionBytes: int(0, Number.MAX_SAFE_INTEGER),
  ffmpeg: z.string().min(1),
  logLevel: z.enum(['fatal', 'error', 'warn', 'info', 'debug', 'trace', 'silent']),
});

/** Thrown by loadConfig; the message names every bad variable. */
export class ConfigError extends Error {
  override name = 'ConfigError';
}

/**
 * Builds the config from an environment (`process.env` by default). An unset or empty
 * variable takes its default; an invalid one throws a ConfigError naming the variable.
 */
export function loadConfig(
  env: Record<string, string | undefined> = process.env,
): MiddlewareConfig {
  const raw: Record<string, string> = {};
  for (const [key, name] of Object.entries(CONFIG_ENV) as [keyof MiddlewareConfig, string][]) {
    const value = env[name]?.trim();
    raw[key] = value ? value : String(DEFAULT_MIDDLEWARE_CONFIG[key]);
  }
  const parsed = SCHEMA.safeParse(raw);
  if (!parsed.success) {
    const lines = parsed.error.issues.map((issue) => {
      const key = issue.path[0] as keyof MiddlewareConfig;
      return `${CONFIG_ENV[key]}=${JSON.stringify(raw[key])}: ${issue.message}`;
    });
    throw new ConfigError(`invalid configuration:\n  ${lines.join('\n  ')}`);
  }
  return parsed.data;
}

/** Where the history API and the export read: the INFLUX_* settings as a reader's source. */
export function influxSource(config: MiddlewareConfig, timeoutMs: number): InfluxSource {
  return {
    url: config.influxUrl,
    token: config.influxToken,
    org: config.influxOrg,
    bucket: config.influxBucket,
    timeoutMs,
  };
}
