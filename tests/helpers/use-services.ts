/**
 * Vitest hooks around the services of `./services.ts`. Call at the top of a test file or a
 * `describe`: the service starts in `beforeAll` and is disposed in `afterAll`, keeping its
 * logs (test-results/services/…) when any test, hook or the suite itself failed.
 */
import { afterAll, beforeAll } from 'vitest';
import { startInflux, type InfluxOptions, type InfluxService } from './influx.ts';
import { startMosquitto, type MosquittoOptions, type MosquittoService } from './mosquitto.ts';

interface TaskLike {
  result?: { state?: string };
  tasks?: readonly TaskLike[];
}

/** True if the suite, or any test or suite inside it, failed. */
export function hasFailed(task: TaskLike): boolean {
  return task.result?.state === 'fail' || (task.tasks ?? []).some(hasFailed);
}

function useService<T extends { dispose(o: { keepLogs: boolean }): Promise<string | undefined> }>(
  name: string,
  start: () => Promise<T>,
): () => T {
  let service: T | undefined;
  beforeAll(async () => {
    service = await start();
  });
  // Vitest parses a hook's first parameter for fixtures: it must be a destructuring pattern.
  // eslint-disable-next-line no-empty-pattern
  afterAll(async ({}, suite) => {
    const kept = await service?.dispose({ keepLogs: hasFailed(suite) });
    if (kept) console.error(`${name} logs kept in ${kept}`);
    service = undefined;
  });
  return () => {
    if (!service) throw new Error(`${name} is not running: use it inside a test or hook`);
    return service;
  };
}

/** A throwaway Mosquitto for the enclosing file or describe; call the result to get it. */
export function useMosquitto(opts?: MosquittoOptions): () => MosquittoService {
  return useService('mosquitto', () => startMosquitto(opts));
}

/** A throwaway influxd for the enclosing file or describe; call the result to get it. */
export function useInflux(opts?: InfluxOptions): () => InfluxService {
  return useService('influxd', () => startInflux(opts));
}
