/**
 * `armtwin up` (what `npm start` runs): the embedded broker, ONE HTTP(S) server (the HUD's
 * files, MQTT over WebSockets at /mqtt, and armtwin's one HTTP API under /api
 * (`@armtwin/http-api`: the middleware's history and metrics, robot writes, model copies), the
 * simulated arm (and the SO-101 on an emulated servo bus behind the bus gateway:
 * ./so101-part.ts), and the middleware with its storage, each as far as it exists. The arm and the middleware connect to
 * the broker in-process (no socket, no password) with the device and middleware roles.
 * `stop()` takes them down in order: the sim says offline, the middleware flushes, influxd
 * stops, the broker and server close.
 *
 * Security (SECURITY.md): without a users file this is the anonymous local demo and the broker
 * refuses any non-loopback host. With one, every MQTT client logs in, and /api (but /healthz)
 * needs a user's name and password (HTTP Basic) or, to read, the API token as a bearer token:
 * the API's one log-in step, on the broker's log-ins and throttle.
 */
import { randomBytes } from 'node:crypto';
import fs from 'node:fs';
import http from 'node:http';
import https from 'node:https';
import path from 'node:path';
import type { Users } from '@armtwin/auth';
import { startBroker, type Broker, type BrokerTls } from '@armtwin/broker';
import { createApi } from '@armtwin/http-api';
import { isModelArmId, linkOptions, MODEL_ARM_SUFFIX } from '@armtwin/protocol';
import {
  DEFAULT_PROFILE,
  loadSimProfile,
  MODELS_DIR,
  simWill,
  startMqttSim,
  followZones,
  type MqttSim,
} from '@armtwin/sim';
import type { ArmtwinFoxglove } from '@armtwin/foxglove';
import { createCameraPart } from './camera-part.ts';
import { startFoxglovePart } from './foxglove-part.ts';
import { ensureWebBuild, startMiddlewarePart, WEB_DIST, type StartedMiddleware } from './parts.ts';
import type { ModelCopies } from './model-copies.ts';
import { createModelPart } from './model-part.ts';
import { SO101_ARM, startSo101Part, type So101Part } from './so101-part.ts';
import { staticFiles } from './static-files.ts';
import { DEFAULT_HUD_HEADERS_OPTIONS, securityHeaders } from './security-headers.ts';

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
  /**
   * The simulated arms and their profiles (`--arms arm1:armtwin5,arm2:track6`), all on this
   * broker; `sim` is the first. Unset or empty: one arm, `armId`, with the default profile.
   */
  arms?: { id: string; profile: string }[];
  /**
   * The second arm, a simulated SO-101 on an emulated Feetech bus behind the real bus gateway
   * (./so101-part.ts), on this arm id; unset: none. `armtwin up` starts it as `so101` unless
   * `--no-so101`. If it cannot start (no socat), `up` says why and runs without it.
   */
  so101?: string;
  /** INFLUX_URL ('' = local influxd if possible). */
  influxUrl: string;
  /** Build the HUD if it is missing. */
  buildWeb: boolean;
  /** Start the middleware. */
  middleware: boolean;
  /** The environment handed to the middleware's own config loader. */
  env: Record<string, string | undefined>;
  /** Users and roles (null = the anonymous local demo, loopback only). */
  users: Users | null;
  /** HTTPS/WSS and MQTTS with this certificate (null = plain). */
  tls: BrokerTls | null;
  /** API_TOKEN: a bearer token that reads /api's history and metrics ('' = none). */
  apiToken: string;
  /**
   * An extra folder of robot profiles (`--models DIR`): served at /models/ before
   * public/models, and searched first for the arms' profiles.
   */
  modelsDir?: string;
  /** The live Foxglove WebSocket server's port (`--foxglove [PORT]`; unset: none; 0: any free). */
  foxglovePort?: number;
  /** A demo camera of the first arm (`--camera testsrc`, a device, a URL; '' = none). */
  camera?: string;
  /**
   * Sources beyond this origin the HUD may connect to and show pictures from (other brokers,
   * camera servers), added to its Content-Security-Policy (./security-headers.ts).
   */
  cspSources?: string[];
  /**
   * A model copy (`/api/arms/{id}/model`, ./model-copies.ts) stops after this long with nothing
   * received on its topics, ms (unset: `DEFAULT_MODEL_COPIES_OPTIONS`, 10 minutes).
   */
  modelIdleMs?: number;
  /** Progress lines for the operator. */
  say: (msg: string) => void;
  onFirst: (kind: string, message: string) => void;
}

export interface Up {
  /** The URL to open. */
  url: string;
  broker: Broker;
  sim: MqttSim;
  /** Every simulated arm, in `arms` order. */
  sims: MqttSim[];
  /** The SO-101 on its emulated bus (`so101`), null when not asked for or when it failed to start. */
  so101: So101Part | null;
  /** The arms' model copies, started on demand (docs/protocol.md § Modes). */
  copies: ModelCopies;
  /** The live Foxglove server (`foxglovePort`), or null. */
  foxglove: ArmtwinFoxglove | null;
  /** Resolves when the middleware (if any) is up or has failed to start. */
  middlewareReady: Promise<StartedMiddleware | null>;
  stop(): Promise<void>;
}

export async function startUp(o: UpOptions): Promise<Up> {
  const armSpecs = o.arms?.length ? o.arms : [{ id: o.armId, profile: DEFAULT_PROFILE }];
  if (o.so101 && armSpecs.some((a) => a.id === o.so101))
    throw new Error(
      `arm id "${o.so101}" is the SO-101 on the emulated bus: give the simulated arm another id, or leave the SO-101 out (--no-so101)`,
    );
  for (const a of armSpecs)
    if (isModelArmId(a.id))
      throw new Error(
        `arm id "${a.id}": ids ending in ${MODEL_ARM_SUFFIX} are reserved for model copies (docs/protocol.md § Modes)`,
      );
  const modelDirs = o.modelsDir ? [o.modelsDir, MODELS_DIR] : [MODELS_DIR];
  // a bad profile fails here, before anything starts
  const profiles = armSpecs.map((a) => loadSimProfile(a.profile, profileDir(modelDirs, a.profile)));
  const hasWeb = o.buildWeb ? ensureWebBuild(o.say) : false;
  const broker = await startBroker({
    host: o.host,
    port: o.mqttPort,
    fallbackToFreePort: o.mqttPortFallback,
    users: o.users,
    tls: o.tls,
    onDenied: (what, detail) =>
      o.onFirst(`denied:${what}`, `${what} refused ${JSON.stringify(detail)}`),
  });
  if (broker.fellBack)
    o.say(`broker: port ${o.mqttPort} is taken; MQTT/TCP on ${broker.port} instead`);

  let mw: StartedMiddleware | null = null;
  const files = staticFiles(
    WEB_DIST,
    'The HUD is not built: run `npm run build -w @armtwin/web`.\n',
  );
  const model = createModelPart({
    broker,
    simulated: new Map(
      armSpecs.map((a) => [
        a.id,
        { profile: a.profile, modelsDir: profileDir(modelDirs, a.profile) },
      ]),
    ),
    modelDirs,
    rate: o.rate,
    ...(o.modelIdleMs ? { idleMs: o.modelIdleMs } : {}),
    onFirst: o.onFirst,
    say: o.say,
  });
  const api = createApi({
    // Without a users file this is the local demo: the broker refuses any non-loopback host.
    auth: { logins: broker.logins, apiToken: o.apiToken, anonymous: 'anywhere' },
    service: () => mw?.middleware.service ?? null,
    modelDirs,
    modelCopies: model.copies,
    onFirst: o.onFirst,
  });
  // The in-process middleware has no password to send the camera server: a token of this run,
  // never stored, lets its recording watch the camera as the middleware role may.
  const recorderToken = randomBytes(32).toString('base64url');
  const camera = o.camera
    ? createCameraPart({
        source: o.camera,
        armId: armSpecs[0]!.id,
        broker,
        apiToken: o.apiToken,
        recorderToken,
        say: o.say,
        onFirst: o.onFirst,
      })
    : null;
  const headers = Object.entries(
    securityHeaders({ ...DEFAULT_HUD_HEADERS_OPTIONS, extraSources: o.cspSources ?? [] }),
  );
  const onRequest = (req: http.IncomingMessage, res: http.ServerResponse) => {
    for (const [name, value] of headers) res.setHeader(name, value);
    if (camera?.handleRequest(req, res)) return;
    if (req.url === '/api' || req.url?.startsWith('/api/')) {
      if (!api.handle(req, res))
        res
          .writeHead(404, { 'content-type': 'application/json', 'cache-control': 'no-store' })
          .end(JSON.stringify({ error: 'not found' }));
      return;
    }
    // The robot folders (`/models/…`) are the API's too; everything else is the HUD's.
    if (req.url?.startsWith('/models/') && api.handle(req, res)) return;
    files(req, res);
  };
  const server = o.tls
    ? https.createServer({ ...o.tls, minVersion: 'TLSv1.2' }, onRequest)
    : http.createServer(onRequest);
  broker.attach(server, camera ? [camera.handleUpgrade] : []);
  try {
    await new Promise<void>((resolve, reject) => {
      server.once('error', reject);
      server.listen(o.httpPort, o.host, () => resolve());
    });
  } catch (err) {
    await camera?.stop();
    await broker.close();
    throw (err as NodeJS.ErrnoException).code === 'EADDRINUSE'
      ? new Error(`HTTP port ${o.httpPort} is taken: set ARMTWIN_PORT to another port`)
      : err;
  }
  const address = server.address();
  const httpPort = typeof address === 'object' && address ? address.port : o.httpPort;
  const shownHost = o.host === '0.0.0.0' || o.host === '::' ? 'localhost' : o.host;
  const url = `${o.tls ? 'https' : 'http'}://${shownHost}:${httpPort}/`;
  camera?.announce(url.slice(0, -1));
  let foxglove: ArmtwinFoxglove | null = null;
  if (o.foxglovePort !== undefined) {
    try {
      foxglove = await startFoxglovePart({
        broker,
        port: o.foxglovePort,
        host: o.host,
        tls: o.tls,
        modelDirs,
        onFirst: o.onFirst,
      });
      o.say(`foxglove: live at ${foxglove.url} (docs/foxglove.md)`);
    } catch (err) {
      await camera?.stop();
      await broker.close();
      server.close();
      throw err;
    }
  }

  const sims = armSpecs.map(({ id }, k) => {
    const client = broker.connectInProcess(
      { name: `sim-${id}`, role: 'device', arm: id },
      {
        clientId: `armtwin-sim-${id}`,
        will: simWill(id),
        ...linkOptions(),
        queueQoSZero: false,
      },
    );
    const profile = profiles[k]!;
    const started = startMqttSim(client, {
      armId: id,
      rate: o.rate,
      onFirst: o.onFirst,
      model: profile.model,
      profile,
    });
    // Zones edited in the HUD (PUT …/keep-out) reach this sim through the profile file.
    const name = armSpecs[k]!.profile;
    const zones = followZones({
      client,
      armId: id,
      name,
      modelsDir: profileDir(modelDirs, name),
      sim: profile,
      runner: started.runner,
      onFirst: o.onFirst,
    });
    const stop = () => {
      zones.stop();
      return started.stop();
    };
    return { ...started, stop };
  });
  const sim = sims[0]!;
  const so101 = o.so101
    ? await startSo101Part({
        broker,
        armId: o.so101,
        profile: SO101_ARM.profile,
        modelsDir: profileDir(modelDirs, SO101_ARM.profile),
        onFirst: o.onFirst,
      }).catch((err: unknown) => {
        o.say(
          `SO-101 "${o.so101}": not started: ${err instanceof Error ? err.message : String(err)}`,
        );
        return null;
      })
    : null;

  const middlewareReady = o.middleware
    ? startMiddlewarePart(
        {
          mqttUrl: broker.url,
          connect: (_url, opts) =>
            broker.connectInProcess({ name: 'middleware', role: 'middleware' }, opts),
          modelDirs,
          cameraAuthorization: `Bearer ${recorderToken}`,
          // its camera server's https/wss URLs carry the up's own (maybe self-signed) certificate
          cameraCa: o.tls?.cert ?? null,
        },
        o.influxUrl,
        o.env,
        o.say,
      ).then(
        (started) => {
          mw = started;
          o.say(`middleware: running; storage: ${started.storage}`);
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
      await foxglove?.stop();
      await camera?.stop();
      await model.stop();
      await Promise.all([...sims.map((s) => s.stop()), so101?.stop()]);
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

  return { url, broker, sim, sims, so101, copies: model.copies, foxglove, middlewareReady, stop };
}

/** The first of `dirs` that holds `<name>/profile.json` (the last one otherwise, for its error). */
function profileDir(dirs: readonly string[], name: string): string {
  return dirs.find((d) => fs.existsSync(path.join(d, name, 'profile.json'))) ?? dirs.at(-1)!;
}
