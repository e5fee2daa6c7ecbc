/**
 * `armtwin up` (what `npm start` runs): the embedded broker, ONE HTTP server (the HUD's files,
 * MQTT over WebSockets at /mqtt, the middleware under /api), the simulated arm, and the
 * middleware with its storage, each as far as it exists. `stop()` takes them down in order:
 * the sim says offline, the middleware flushes, influxd stops, the broker and server close.
 */
import http from 'node:http';
import mqtt from 'mqtt';
import { startBroker, type Broker } from '../broker/broker.ts';
import { simWill, startMqttSim, type MqttSim } from '../sim/mqtt-sim.ts';
import { ensureWebBuild, startMiddlewarePart, WEB_DIST, type StartedMiddleware } from './parts.ts';
import { staticFiles } from './static-files.ts';

export interface UpOptions {
  /** The HTTP port: HUD, /mqtt, /api. 0 = any free port. */
  httpPort: number;
  /** The broker's MQTT/TCP port. */
  mqttPort: number;
  /** Fall back to a free MQTT port when `mqttPort` is taken (when it was not asked for explicitly). */
  mqttPortFallback: boolean;
  host: string;
  /** The simulated arm's id and state rate. */
  armId: string;
  rate: number;
  /** INFLUX_URL ('' = local influxd if possible). */
  influxUrl: string;
  /** Build the HUD if it is missing. */
  buildWeb: boolean;
  /** Start the middleware (if it exists). */
  middleware: boolean;
  /** The environment handed to the middleware's own config loader. */
  env: Record<string, string | undefined>;
  /** Progress lines for the operator. */
  say: (msg: string) => void;
  onFirst: (kind: string, message: string) => void;
}

export interface Up {
  /** The URL to open. */
  url: string;
  broker: Broker;
  sim: MqttSim;
  /** Resolves when the middleware (if any) is up or has failed to start. */
  middlewareReady: Promise<StartedMiddleware | null>;
  stop(): Promise<void>;
}

const MIDDLEWARE_MISSING = JSON.stringify({
  ok: false,
  storage: false,
  error: 'the middleware is not running',
});

export async function startUp(o: UpOptions): Promise<Up> {
  const hasWeb = o.buildWeb ? ensureWebBuild(o.say) : false;
  const broker = await startBroker({
    host: o.host,
    port: o.mqttPort,
    fallbackToFreePort: o.mqttPortFallback,
  });
  if (broker.fellBack)
    o.say(`broker: port ${o.mqttPort} is taken; MQTT/TCP on ${broker.port} instead`);

  let mw: StartedMiddleware | null = null;
  const files = staticFiles(
    WEB_DIST,
    'The HUD is not built: run `npm run build -w @armtwin/web`.\n',
  );
  const server = http.createServer((req, res) => {
    if (req.url === '/api' || req.url?.startsWith('/api/')) {
      if (mw?.middleware.handler(req, res)) return;
      res.writeHead(mw ? 404 : 503, {
        'content-type': 'application/json',
        'cache-control': 'no-store',
      });
      res.end(mw ? JSON.stringify({ error: 'not found' }) : MIDDLEWARE_MISSING);
      return;
    }
    files(req, res);
  });
  broker.attach(server);
  try {
    await new Promise<void>((resolve, reject) => {
      server.once('error', reject);
      server.listen(o.httpPort, o.host, () => resolve());
    });
  } catch (err) {
    await broker.close();
    throw (err as NodeJS.ErrnoException).code === 'EADDRINUSE'
      ? new Error(`HTTP port ${o.httpPort} is taken: set ARMTWIN_PORT to another port`)
      : err;
  }
  const address = server.address();
  const httpPort = typeof address === 'object' && address ? address.port : o.httpPort;
  const shownHost = o.host === '0.0.0.0' || o.host === '::' ? 'localhost' : o.host;
  const url = `http://${shownHost}:${httpPort}/`;

  const client = mqtt.connect(broker.url, {
    clientId: `armtwin-sim-${o.armId}`,
    will: simWill(o.armId),
    reconnectPeriod: 1000,
    queueQoSZero: false,
  });
  const sim = startMqttSim(client, { armId: o.armId, rate: o.rate, onFirst: o.onFirst });

  const middlewareReady = o.middleware
    ? startMiddlewarePart(broker.url, o.influxUrl, o.env, o.say).then(
        (started) => {
          mw = started;
          if (started) o.say(`middleware: running; storage: ${started.storage}`);
          return started;
        },
        (err: unknown) => {
          o.say(`middleware: failed to start: ${err instanceof Error ? err.message : String(err)}`);
          return null;
        },
      )
    : Promise.resolve(null);
  if (!hasWeb && o.buildWeb) o.say('HUD: not available; the page at the URL says why');

  let stopping: Promise<void> | undefined;
  const stop = () =>
    (stopping ??= (async () => {
      await sim.stop();
      const started = await middlewareReady;
      if (started) {
        await started.middleware
          .stop()
          .catch((err: Error) => o.say(`middleware: stop failed: ${err.message}`));
        await started.influx
          ?.stop()
          .catch((err: Error) => o.say(`influxd: stop failed: ${err.message}`));
      }
      const closed = new Promise<void>((resolve) => server.close(() => resolve()));
      await broker.close();
      server.closeAllConnections();
      await closed;
    })());

  return { url, broker, sim, middlewareReady, stop };
}
