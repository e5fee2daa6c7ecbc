/**
 * The middleware's HTTP side: what it lends armtwin's one HTTP API (`@armtwin/http-api`):
 * `/healthz` (JSON, 200 or 503), `/metrics` (Prometheus text) and `/history/…` (./history,
 * present when storage is configured); and the API as the middleware serves it on its own port,
 * robot writes included (calibration, keep-out zones, imports into MODELS_DIR), so a deployment
 * without `armtwin up` has them too. `armtwin up` mounts the same API with this `service`.
 * Log-ins and the API token: `@armtwin/http-api`'s one authorize step (SECURITY.md).
 */
import type { IncomingMessage, ServerResponse } from 'node:http';
import type { LoginThrottle } from '@armtwin/auth';
import {
  createApi,
  type ApiService,
  type CameraSegmentService,
  type EpisodeService,
} from '@armtwin/http-api';
import type { HistoryHandler } from './history/index.ts';
import { renderMetrics, type Metrics } from './metrics.ts';

export interface HealthReport {
  ok: boolean;
  /** `broker`: "Broker 2 of 2: mqtt://…" (docs/protocol.md § Several brokers). */
  mqtt: { connected: boolean; url: string; broker?: string };
  influx: { reachable: boolean; url: string };
  storage: boolean;
  writeMode: 'batch' | 'sync';
  spool: { files: number; points: number; bytes: number; full: boolean; openPoints: number };
  pointsWritten: number;
  pointsDropped: number;
}

/** What the handler needs from a running middleware. */
export interface HttpSource {
  metrics: Metrics;
  health(): HealthReport;
  /** The history API, or null when there is no storage to read from. */
  history?: HistoryHandler | null;
  /** An arm's episode marks, or null when there is no storage. */
  episodes?: EpisodeService | null;
  /** The cameras' recorded segments, or null when not recording. */
  cameras?: CameraSegmentService | null;
  /** '' = open; else the bearer token /metrics and /history require. */
  apiToken?: string;
  /** The users file behind the failed-log-in throttle, or null. */
  logins?: LoginThrottle | null;
  /** Robot folders the robot writes go to (MODELS_DIR; none: robot writes answer 404). */
  modelDirs?: readonly string[];
  /** Told once per kind of refused or failed API request. */
  onFirst?(kind: string, message: string): void;
}

/** What the middleware lends the API (`armtwin up` mounts the API with it). */
export function apiService(mw: HttpSource): ApiService {
  return {
    health: () => mw.health(),
    metrics: () => renderMetrics(mw.metrics),
    history: mw.history ?? null,
    episodes: mw.episodes ?? null,
    cameras: mw.cameras ?? null,
  };
}

export type HttpHandler = (req: IncomingMessage, res: ServerResponse) => boolean;

/** Serves the request if it is one of the API's (returns true), else leaves it (returns false). */
export function createHttpHandler(mw: HttpSource): HttpHandler {
  const service = apiService(mw);
  const api = createApi({
    auth: {
      logins: mw.logins ?? null,
      apiToken: mw.apiToken ?? '',
      // Without a users file, anonymous callers change robots from this machine only.
      anonymous: 'loopback',
    },
    service: () => service,
    modelDirs: mw.modelDirs ?? [],
    modelCopies: null,
    onFirst: mw.onFirst ?? (() => {}),
  });
  return api.handle;
}
