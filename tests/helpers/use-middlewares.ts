/**
 * Vitest hook for the middleware processes of one test file: `spawn()` starts one (a child
 * process, so it can be SIGKILLed) in the file's temp dir with its own client id, spool and
 * log; after all tests every one is stopped and the dir removed.
 */
import fs from 'node:fs';
import path from 'node:path';
import { afterAll } from 'vitest';
import { freePort } from './ports.ts';
import {
  middlewareEnv,
  spawnMiddleware,
  tempDir,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';

/** The broker, and InfluxDB (omitted: the middleware runs without storage). */
export type MiddlewareServices = Parameters<typeof middlewareEnv>[0];

export interface SpawnOptions {
  /** Extra environment (FLUSH_INTERVAL_MS, …). */
  env?: Record<string, string>;
  /** MQTT client id and log name; default: the file's name. */
  clientId?: string;
  /** HTTP port; default: a free one. */
  port?: number;
}

export interface Middlewares {
  /** The file's temp dir (made on first use). */
  dir(): string;
  /** The log of the instance with this client id. */
  log(clientId?: string): string;
  spawn(options?: SpawnOptions): Promise<MiddlewareProcess>;
}

export function useMiddlewares(name: string, services: () => MiddlewareServices): Middlewares {
  let dir = '';
  const running: MiddlewareProcess[] = [];
  afterAll(async () => {
    await Promise.all(running.map((m) => m.stop()));
    if (dir) fs.rmSync(dir, { recursive: true, force: true });
  });
  const folder = () => (dir ||= tempDir(name));
  const log = (clientId = name) => path.join(folder(), `${clientId}.log`);
  return {
    dir: folder,
    log,
    async spawn({ env = {}, clientId = name, port }: SpawnOptions = {}) {
      const mw = await spawnMiddleware(
        middlewareEnv(services(), clientId, folder(), env, `spool-${clientId}`),
        port ?? (await freePort()),
        log(clientId),
      );
      running.push(mw);
      return mw;
    },
  };
}
