/**
 * Fixtures for the History panel and replay: the HUD fixtures of ./fixtures.ts plus storage.
 * The worker's `stack` is overridden: the same Mosquitto, and also a throwaway influxd, the
 * middleware as a child process (`node --import tsx apps/middleware/src/main.ts`, writing
 * every 200 ms, recording announced cameras in 2 s segments), and the built HUD served with `/api/*` proxied to the middleware, as
 * `npm start` serves it (same origin, so the HUD's default API base `/api` works, no CORS).
 * Files that import this `test` get their own worker; ./hud-*.spec.ts keep the plain stack.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { test as base, expect, type Stack } from './fixtures.ts';
import { freePort, startInflux, type InfluxService } from '../helpers/services.ts';
import {
  spawnMiddleware,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';
import { HUD_DIST } from './support/build-hud.ts';
import { serveStatic } from './support/static-server.ts';

export interface StorageStack extends Stack {
  influx: InfluxService;
  middleware: MiddlewareProcess;
  /** The middleware's API, straight (not through the proxy): `http://127.0.0.1:<port>/api`. */
  apiUrl: string;
}

export const test = base.extend<object, { stack: StorageStack }>({
  stack: [
    async ({ stack }, use, workerInfo) => {
      const influx = await startInflux();
      const spoolDir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-spool-'));
      const cameraDir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-cameras-'));
      const logFile = path.join(workerInfo.project.outputDir, `middleware-${process.pid}.log`);
      fs.mkdirSync(path.dirname(logFile), { recursive: true });
      let middleware: MiddlewareProcess | undefined;
      let failed = false;
      try {
        middleware = await spawnMiddleware(
          {
            MQTT_URL: stack.broker.url,
            MQTT_CLIENT_ID: `e2e-middleware-${process.pid}`,
            INFLUX_URL: influx.url,
            INFLUX_BUCKET: influx.bucket,
            FLUSH_INTERVAL_MS: '200',
            SPOOL_DIR: spoolDir,
            // Cameras a test announces are recorded, in short segments (./history-video.spec.ts).
            CAMERA_DIR: cameraDir,
            CAMERA_SEGMENT_S: '2',
          },
          await freePort(),
          logFile,
        );
        const target = `http://127.0.0.1:${middleware.port}`;
        const web = await serveStatic(HUD_DIST, { proxy: { prefix: '/api/', target } });
        try {
          const storage: StorageStack = {
            ...stack,
            web,
            influx,
            middleware,
            apiUrl: `${target}/api`,
          };
          await use(storage);
        } finally {
          await web.close();
        }
      } catch (err) {
        failed = true;
        throw err;
      } finally {
        await middleware?.stop();
        await influx.dispose({ keepLogs: failed || Boolean(process.env.ARMTWIN_KEEP_LOGS) });
        fs.rmSync(spoolDir, { recursive: true, force: true });
        fs.rmSync(cameraDir, { recursive: true, force: true });
      }
    },
    { scope: 'worker', timeout: 180_000 },
  ],
});

export { expect };

/** GET `<apiUrl>/history/<endpoint>?<query>` → JSON (throws on a non-2xx answer). */
export async function historyGet<T>(
  stack: StorageStack,
  endpoint: string,
  query: Record<string, string>,
): Promise<T> {
  const res = await fetch(`${stack.apiUrl}/history/${endpoint}?${new URLSearchParams(query)}`);
  if (!res.ok) throw new Error(`${endpoint}: HTTP ${res.status} ${await res.text()}`);
  return (await res.json()) as T;
}
