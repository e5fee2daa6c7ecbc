/**
 * Vitest hooks around the services of `./services.ts`. Call at the top of a test file or a
 * `describe`: the service starts in `beforeAll` and is disposed in `afterAll`, keeping its
 * logs (test-results/services/…) when any test, hook or the suite itself failed.
 */
import { afterAll, beforeAll } from 'vitest';
import { startInflux, type InfluxOptions, type InfluxService } from './influx.ts';
import { startInflux2, type Influx2Service } from './influx2.ts';
import { startMosquitto, type MosquittoOptions, type MosquittoService } from './mosquitto.ts';
import { startNatsCluster, type NatsCluster } from './nats-cluster.ts';

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

/** A throwaway 3-node NATS cluster (JetStream, MQTT, MQTT over WebSockets) on 127.0.0.1. */
export function useNatsCluster(): () => NatsCluster {
  return useService('nats-cluster', startNatsCluster);
}

/** A throwaway influxd for the enclosing file or describe; call the result to get it. */
export function useInflux(opts?: InfluxOptions): () => InfluxService {
  return useService('influxd', () => startInflux(opts));
}

/** A throwaway InfluxDB 2.7 (set up, token auth on) for the enclosing file or describe. */
export function useInflux2(): () => Influx2Service {
  return useService('influxd2', startInflux2);
}

/** What a client needs of either server through the v2 API (1.8: org '' and token ''). */
export interface InfluxEndpoint {
  url: string;
  org: string;
  bucket: string;
  token: string;
}

/**
 * The InfluxDB servers the storage tests run against, each started per describe:
 * `describe.each(INFLUX_SERVERS)('InfluxDB $version', ({ use }) => { const influx = use(); … })`.
 */
export const INFLUX_SERVERS: { version: string; use: () => () => InfluxEndpoint }[] = [
  { version: '1.8', use: () => useInflux() },
  { version: '2.7', use: () => useInflux2() },
];
