/**
 * `startMiddleware(config, deps?)`: MQTT → cleaner → durable spool → InfluxDB, plus the HTTP
 * endpoints. The orchestrator (`npm start`) and the tests call this; `main.ts` is the CLI.
 */
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { MODELS_DIR } from '@armtwin/motion/robot-folder';
import { SYSTEM_CLOCK, type Clock } from '@armtwin/protocol';
import { describeBroker, redactBrokerUrl } from '@armtwin/link';
import { LoginThrottle, loadUsers } from '@armtwin/auth';
import { ConfigError, influxSource, type MiddlewareConfig } from './config.ts';
import { createHistoryHandler, type HistoryHandlerDeps } from './history/index.ts';
import { historyReader } from './history/reader.ts';
import { loadRecordingRobot } from './export/index.ts';
import { apiService, createHttpHandler, type HealthReport, type HttpHandler } from './http.ts';
import { createInfluxWriter, gzipLevelFor, type InfluxWriter } from './influx.ts';
import { Ingest } from './ingest.ts';
import { createLogger, LogOnce, type Logger } from './log.ts';
import { Metrics } from './metrics.ts';
import type { ConnectFn } from './mqtt.ts';
import { startIntake } from './intake.ts';
import { Storage } from './storage.ts';
import { episodeStore } from './episodes/store.ts';
import type { ApiService } from '@armtwin/http-api';
import { startThermalAlerts } from './thermal-alerts-run.ts';
import { startMiddlewareFoxglove } from './foxglove.ts';
import type { ArmtwinFoxglove } from '@armtwin/foxglove';
import { startRecordings } from './cameras/index.ts';

export {
  loadConfig,
  DEFAULT_MIDDLEWARE_CONFIG,
  CONFIG_ENV,
  ConfigError,
  influxSource,
  type MiddlewareConfig,
} from './config.ts';
export { apiService, createHttpHandler, type HealthReport, type HttpHandler } from './http.ts';
export {
  historyReader,
  QUERY_LANGUAGES,
  type HistoryReader,
  type InfluxSource,
  type QueryLanguage,
} from './history/reader.ts';
export { renderMetrics, Metrics } from './metrics.ts';
export { startLocalInflux, type LocalInflux } from './local-influx.ts';

export interface MiddlewareDeps {
  logger?: Logger;
  /** The InfluxDB edge (a fake in unit tests); default: built from the config. */
  writer?: InfluxWriter;
  /** mqtt.js `connect` (a fake in unit tests). */
  connect?: ConnectFn;
  clock?: Clock;
  /** Wall clock, epoch ms: the time of frames that carry no `$TIM`. */
  now?: () => number;
  /** Open the HTTP port (default true). The orchestrator mounts `handler` instead. */
  listen?: boolean;
  /** A profile's robot for the history API's MCAP export (default: from `modelDirs`). */
  robotFor?: HistoryHandlerDeps['robotFor'];
  /**
   * The robot folders, searched in order (default: MODELS_DIR, else `public/models`): where the
   * HTTP API's robot writes go and the MCAP export reads.
   */
  modelDirs?: readonly string[];
  /**
   * The `Authorization` header the camera recording sends to camera servers when the middleware
   * has no MQTT log-in of its own to send (`armtwin up`'s in-process middleware: a token its
   * camera server takes); MQTT_USERNAME/MQTT_PASSWORD, where set, are sent instead.
   */
  cameraAuthorization?: string;
  /**
   * A certificate (PEM) the camera recording trusts besides the usual roots: `armtwin up` with
   * ARMTWIN_TLS_CERT passes its own, so its in-process middleware records its own camera server.
   */
  cameraCa?: Buffer;
}

export interface Middleware {
  readonly config: MiddlewareConfig;
  readonly metrics: Metrics;
  /** Bound HTTP port, or null when not listening. */
  readonly httpPort: number | null;
  /** The live Foxglove server (FOXGLOVE_PORT), or null. */
  readonly foxglove: ArmtwinFoxglove | null;
  /** The HTTP API as the middleware serves it on its own port. */
  readonly handler: HttpHandler;
  /** What it lends the HTTP API (`armtwin up` mounts the API with it). */
  readonly service: ApiService;
  health(): HealthReport;
  /** Seals the open batch and waits until the spool is empty or `timeoutMs` passes. */
  flush(timeoutMs?: number): Promise<boolean>;
  /** Stops intake, seals and writes what it can within `timeoutMs`; the rest stays spooled. */
  stop(timeoutMs?: number): Promise<void>;
}

export async function startMiddleware(
  config: MiddlewareConfig,
  deps: MiddlewareDeps = {},
): Promise<Middleware> {
  const log = deps.logger ?? createLogger(config.logLevel);
  const logins = config.usersFile ? new LoginThrottle(usersFrom(config.usersFile)) : null;
  const once = new LogOnce(log);
  const clock = deps.clock ?? SYSTEM_CLOCK;
  const now = deps.now ?? Date.now;
  const metrics = new Metrics();
  const ingest = new Ingest(metrics, once, { maxPayloadBytes: config.maxPayloadBytes });
  let stopped = false;

  let storage: Storage | null = null;
  let writer: InfluxWriter | null = null;
  if (deps.writer ?? config.influxUrl) {
    writer =
      deps.writer ??
      createInfluxWriter({
        url: config.influxUrl,
        token: config.influxToken,
        org: config.influxOrg,
        bucket: config.influxBucket,
        timeoutMs: 10_000,
        gzipLevel: gzipLevelFor(config.writeGzip, config.writeGzipLevel, config.influxUrl),
      });
    storage = new Storage(config, writer, metrics, log, once, clock);
    log.info(
      {
        url: config.influxUrl,
        bucket: config.influxBucket,
        mode: config.writeMode,
        batchSize: config.batchSize,
        flushIntervalMs: config.flushIntervalMs,
        gzipLevel: gzipLevelFor(config.writeGzip, config.writeGzipLevel, config.influxUrl),
      },
      'storage: InfluxDB',
    );
    storage.start();
  } else {
    log.warn(
      'storage: none (INFLUX_URL is not set): frames are cleaned and counted but NOT stored',
    );
  }
  metrics.storageEnabled = storage !== null;

  // The thermal model's early warnings (docs/protocol.md § A thermal model of each servo); it
  // fits from the history, so it needs storage.
  const heat =
    storage && config.influxUrl && config.thermalWatch && !config.mqttShareGroup && !config.natsUrl
      ? startThermalAlerts(
          { refitMs: config.thermalRefitMs },
          {
            reader: historyReader(influxSource(config, 30_000), config.influxQueryLanguage),
            store: (lines) => storage?.add(lines),
            clock: ingest.clock,
            publish: (topic, payload) => client.publish(topic, payload, { qos: 1 }),
            now,
            log,
            once,
          },
        )
      : null;
  if (heat) ingest.onStatusFrames = (arm, frames) => heat.frames(arm, frames);

  // Every announced camera recorded beside the history (docs/cameras-recording.md).
  const recordings =
    config.cameraRecord && !config.mqttShareGroup && !config.natsUrl
      ? startRecordings(config, log, now, deps.cameraAuthorization, deps.cameraCa)
      : null;
  metrics.cameras = recordings?.counters ?? null;

  // Over MQTT, or from a NATS cluster's JetStream (NATS_URL): ./intake.ts.
  const client = startIntake(config, {
    ingest,
    storage,
    recordings,
    metrics,
    log,
    once,
    now,
    stopped: () => stopped,
    connect: deps.connect,
  });

  const pingTimer = writer
    ? setInterval(() => {
        writer.ping().then(
          (ok) => (metrics.influxReachable = ok),
          () => (metrics.influxReachable = false),
        );
      }, 5000)
    : null;
  pingTimer?.unref();

  const health = (): HealthReport => {
    const spool = storage?.spool;
    metrics.spoolFiles = spool?.queue.length ?? 0;
    metrics.spoolPoints = spool?.sealedPoints ?? 0;
    metrics.spoolBytes = spool?.bytes ?? 0;
    const influxOk = !storage || metrics.influxReachable;
    return {
      ok: metrics.mqttConnected && influxOk && !metrics.spoolFull,
      mqtt: {
        connected: metrics.mqttConnected,
        url: redactBrokerUrl(client.brokers.choice.url),
        broker: describeBroker(client.brokers.choice),
      },
      influx: { reachable: storage !== null && metrics.influxReachable, url: config.influxUrl },
      storage: storage !== null,
      writeMode: config.writeMode,
      spool: {
        files: metrics.spoolFiles,
        points: metrics.spoolPoints,
        bytes: metrics.spoolBytes,
        full: metrics.spoolFull,
        openPoints: spool?.pendingPoints ?? 0,
      },
      pointsWritten: metrics.pointsWritten,
      pointsDropped: metrics.pointsDropped,
    };
  };

  const modelDirs = deps.modelDirs ?? [config.modelsDir || MODELS_DIR];
  const robotFor =
    deps.robotFor ??
    ((name: string) =>
      loadRecordingRobot(
        name,
        modelDirs.find((d) => fs.existsSync(path.join(d, name, 'profile.json'))) ?? modelDirs[0],
      ));
  const history = config.influxUrl
    ? createHistoryHandler({
        reader: historyReader(influxSource(config, 30_000), config.influxQueryLanguage),
        robotFor,
        onError: (err) =>
          once.warn(
            'history-query-failed',
            { err: (err as Error).message },
            'history query failed',
          ),
      })
    : null;
  const episodes =
    storage && config.influxUrl
      ? episodeStore({
          reader: historyReader(influxSource(config, 30_000), config.influxQueryLanguage),
          storage,
          now: () => clock.now(),
        })
      : null;
  const source = { metrics, health, history, episodes, cameras: recordings };
  /** The kinds of refused or failed API requests told so far. */
  const apiKinds = new Set<string>();
  const handler = createHttpHandler({
    ...source,
    apiToken: config.apiToken,
    logins,
    modelDirs,
    onFirst: (kind, message) => {
      if (apiKinds.has(kind)) return;
      apiKinds.add(kind);
      log.warn({ kind }, `${message} (logged once per kind)`);
    },
  });
  let server: http.Server | null = null;
  let httpPort: number | null = null;
  if (deps.listen !== false) {
    const srv = http.createServer((req, res) => {
      if (!handler(req, res))
        res.writeHead(404, { 'content-type': 'text/plain' }).end('not found\n');
    });
    await new Promise<void>((resolve, reject) => {
      srv.once('error', reject);
      srv.listen(config.port, config.host, () => resolve());
    });
    const addr = srv.address();
    httpPort = typeof addr === 'object' && addr ? addr.port : null;
    server = srv;
    log.info(
      {
        url: `http://${config.host}:${httpPort}`,
        apiToken: config.apiToken ? 'required' : 'none',
        logIns: logins ? 'users file' : 'none',
      },
      'HTTP: /healthz and /metrics',
    );
  }

  let foxglove: ArmtwinFoxglove | null = null;
  if (config.foxglovePort !== 'off') {
    try {
      foxglove = await startMiddlewareFoxglove({
        config,
        port: config.foxglovePort,
        logins,
        modelDirs,
        onFirst: (kind, message) => once.warn(`foxglove:${kind}`, { kind }, message),
      });
    } catch (err) {
      if (pingTimer) clearInterval(pingTimer);
      heat?.stop();
      server?.close();
      client.end(true, {}, () => {});
      await storage?.stop(1000);
      throw new ConfigError(`FOXGLOVE_PORT: ${(err as Error).message}`, { cause: err });
    }
    log.info({ url: foxglove.url }, 'Foxglove: live (docs/foxglove.md)');
  }

  return {
    config,
    metrics,
    foxglove,
    get httpPort() {
      return httpPort;
    },
    handler,
    service: apiService(source),
    health,
    flush: async (timeoutMs = 10_000) => (storage ? storage.flush(timeoutMs) : true),
    async stop(timeoutMs = 5000) {
      if (stopped) return;
      stopped = true;
      if (pingTimer) clearInterval(pingTimer);
      heat?.stop();
      await foxglove?.stop();
      await recordings?.stop();
      // The samples the broker already sent (an arm stopped just before) go in the last batch.
      if (storage?.gate() == null) await client.settle(2000);
      await new Promise<void>((resolve) => {
        const t = setTimeout(resolve, 2000);
        client.end(storage?.gate() != null, {}, () => (clearTimeout(t), resolve()));
      });
      metrics.mqttConnected = false;
      await storage?.stop(timeoutMs);
      const closing = new Promise<void>((resolve) =>
        server ? server.close(() => resolve()) : resolve(),
      );
      server?.closeAllConnections();
      await closing;
      log.info(
        { pointsWritten: metrics.pointsWritten, pointsDropped: metrics.pointsDropped },
        'middleware stopped',
      );
    },
  };
}

/** The users file, or a ConfigError naming ARMTWIN_USERS (start-up stops with exit code 2). */
function usersFrom(file: string) {
  try {
    return loadUsers(file);
  } catch (err) {
    throw new ConfigError(`ARMTWIN_USERS: ${(err as Error).message}`, { cause: err });
  }
}
