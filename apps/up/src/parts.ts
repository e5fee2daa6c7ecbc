/**
 * The optional parts of `armtwin up`: the HUD's build (found only if this checkout has the HUD's
 * sources; `up` says plainly when it runs without it) and the middleware with its storage (a
 * local influxd when no INFLUX_URL is given). The middleware is imported when it is started, so
 * `--no-middleware` loads none of it.
 */
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import type {
  LocalInflux,
  Middleware,
  MiddlewareConfig,
  MiddlewareDeps,
} from '@armtwin/middleware';

export const REPO_ROOT = path.resolve(
  path.dirname(fileURLToPath(import.meta.url)),
  '..',
  '..',
  '..',
);
export const WEB_DIR = path.join(REPO_ROOT, 'apps', 'web');
export const WEB_DIST = path.join(WEB_DIR, 'dist');
export const LOCAL_INFLUX_DATA = path.join(REPO_ROOT, '.armtwin', 'influx');
export const MIDDLEWARE_SPOOL = path.join(REPO_ROOT, '.armtwin', 'middleware-spool');
export const CAMERA_RECORDINGS = path.join(REPO_ROOT, '.armtwin', 'camera-recordings');

type Say = (msg: string) => void;

/** Builds the HUD when it has sources but no build; returns whether dist/index.html exists. */
export function ensureWebBuild(say: Say): boolean {
  if (fs.existsSync(path.join(WEB_DIST, 'index.html'))) return true;
  const pkg = path.join(WEB_DIR, 'package.json');
  if (!fs.existsSync(pkg) || !fs.existsSync(path.join(WEB_DIR, 'index.html'))) {
    say('HUD: not in this checkout yet (apps/web); the page says so');
    return false;
  }
  say('HUD: apps/web/dist is missing; building it (npm run build -w @armtwin/web)…');
  const r = spawnSync('npm', ['run', 'build', '-w', '@armtwin/web'], {
    cwd: REPO_ROOT,
    stdio: ['ignore', 2, 2],
  });
  const ok = r.status === 0 && fs.existsSync(path.join(WEB_DIST, 'index.html'));
  if (!ok) say('HUD: the build failed (see above); serving without it');
  return ok;
}

type ConnectFn = NonNullable<MiddlewareDeps['connect']>;

/** How the middleware reaches the broker, and where the robot folders are. */
export interface MiddlewareLink {
  /** Shown in /healthz. */
  mqttUrl: string;
  /** Connects its MQTT client (in-process to the embedded broker). */
  connect: ConnectFn;
  /** The folders of robot profiles, searched in order (for the history API's MCAP export). */
  modelDirs: readonly string[];
  /** What its camera recording sends the up's camera server (`Bearer <this run's token>`). */
  cameraAuthorization: string;
  /** The up's own certificate (ARMTWIN_TLS_CERT), which its camera recording trusts; null = plain. */
  cameraCa: Buffer | null;
}

export interface StartedMiddleware {
  middleware: Middleware;
  influx: LocalInflux | null;
  /** Where points go, in words. */
  storage: string;
}

/** ARMTWIN_INFLUX_PORT: the local influxd's HTTP port (its RPC port is 2 above); unset: 8086. */
export function localInfluxPort(text: string | undefined): number | undefined {
  if (!text) return undefined;
  const n = Number(text);
  if (!Number.isInteger(n) || n < 1 || n > 65533)
    throw new Error(`ARMTWIN_INFLUX_PORT=${JSON.stringify(text)}: expected a port 1–65533`);
  return n;
}

/**
 * Starts the middleware on the broker of `link`: storage is INFLUX_URL if given, else a local
 * influxd under .armtwin/influx (ARMTWIN_INFLUX_DATA, on ARMTWIN_INFLUX_PORT) if one can be
 * started, else none. Throws when it fails to start.
 */
export async function startMiddlewarePart(
  link: MiddlewareLink,
  influxUrl: string,
  env: Record<string, string | undefined>,
  say: Say,
): Promise<StartedMiddleware> {
  const mod = await import('@armtwin/middleware');
  let influx: LocalInflux | null = null;
  const dataDir = env.ARMTWIN_INFLUX_DATA || LOCAL_INFLUX_DATA;
  const overrides: Partial<MiddlewareConfig> = {
    mqttUrl: link.mqttUrl,
    spoolDir: env.SPOOL_DIR || MIDDLEWARE_SPOOL,
    cameraDir: env.CAMERA_DIR || CAMERA_RECORDINGS,
    // `armtwin up` serves the HTTP API itself (with the broker's throttle: one lockout for MQTT
    // and /api) and lends it the middleware's `service`: a second users file would go unused.
    usersFile: '',
  };
  if (influxUrl) {
    overrides.influxUrl = influxUrl;
  } else {
    const port = localInfluxPort(env.ARMTWIN_INFLUX_PORT);
    fs.mkdirSync(dataDir, { recursive: true });
    influx = await mod.startLocalInflux({
      dataDir,
      ...(port === undefined ? {} : { port }),
      log: (m) => say(`influxd: ${m}`),
    });
    if (influx)
      Object.assign(overrides, {
        influxUrl: influx.url,
        influxBucket: influx.bucket,
        influxToken: '',
        influxOrg: '',
      });
  }
  const config: MiddlewareConfig = { ...mod.loadConfig(env), ...overrides };
  try {
    const middleware = await mod.startMiddleware(config, {
      listen: false,
      connect: link.connect,
      modelDirs: link.modelDirs,
      cameraAuthorization: link.cameraAuthorization,
      ...(link.cameraCa ? { cameraCa: link.cameraCa } : {}),
    });
    const storage = config.influxUrl
      ? `InfluxDB at ${config.influxUrl}${influx ? ` (local influxd, data in ${path.relative(REPO_ROOT, dataDir)})` : ''}`
      : 'NONE: no INFLUX_URL and no local influxd could be started, so nothing is stored';
    return { middleware, influx, storage };
  } catch (err) {
    await influx?.stop();
    throw err;
  }
}
