/**
 * armtwin's one HTTP API (docs/protocol.md § The HTTP API): one router (find-my-way, the router
 * behind Fastify, on plain node:http) and one log-in step (./authorize.ts) in front of every
 * route. The middleware serves it on its own port; `armtwin up` mounts the same API under `/api`
 * of its one HTTP port. Paths answer with and without the `/api` prefix.
 *
 *   /healthz, /metrics, /history/…      the middleware's (`service`; 503 while it is not running)
 *   /whoami                             the caller's user and role, for the HUD
 *   /robots/import                      POST a robot as a .zip (./robots/import.ts)
 *   /robots/{name}/calibration          PUT (./robots/calibration.ts)
 *   /robots/{name}/keep-out             PUT (./robots/keep-out.ts)
 *   /arms/{id}/episodes                 GET, POST an arm's episode marks (./episodes.ts; 503
 *                                       without the middleware's storage)
 *   /arms/{id}/cameras/{cam}/segments[/{name}]  GET a camera's recorded segments
 *                                       (./camera-segments.ts; 503 without the recording)
 *   /arms/{id}/model                    GET, POST, DELETE a model copy (./model-copies.ts; 501
 *                                       where no `modelCopies` host runs them)
 *   /models/{name}/…                    GET the robot folders' files (./model-files.ts)
 */
import type http from 'node:http';
import Router from 'find-my-way';
import {
  createAuthorize,
  nameOf,
  refusal,
  type AuthOptions,
  type Authorize,
  type Right,
} from './authorize.ts';
import type { May, RouteCounters } from './counted-answer.ts';
import { cameraSegmentsRoute } from './camera-segments.ts';
import { episodesRoute } from './episodes.ts';
import { modelCopyRoute, type ModelCopyHost } from './model-copies.ts';
import { modelFiles } from './model-files.ts';
import { calibrationRoute } from './robots/calibration.ts';
import { importRoute } from './robots/import.ts';
import { keepOutRoute } from './robots/keep-out.ts';
import { sendJson } from './send-json.ts';
import { serviceRoutes, type ApiService } from './service-routes.ts';

export interface ApiOptions {
  auth: AuthOptions;
  /** The middleware's part, or null while there is none (see ./service-routes.ts). */
  service: () => ApiService | null;
  /**
   * Robot folders, searched in order for a robot's profile.json; imports are written into the
   * first. Where the controllers (`armtwin sim`, `armtwin gateway --bus`) read their profiles,
   * and the HUD its `/models/`. None: no robot routes.
   */
  modelDirs: readonly string[];
  /** Runs the model copies (`armtwin up`); null = 501 for `/arms/{id}/model`. */
  modelCopies: ModelCopyHost | null;
  /** Told once per kind of refusal or failure. */
  onFirst(kind: string, message: string): void;
}

export interface Api {
  /**
   * Serves the request when its path (with or without `/api`) is one of the API's (true), else
   * leaves it to the caller (false).
   */
  handle(req: http.IncomingMessage, res: http.ServerResponse): boolean;
  /** The one log-in step. */
  authorize: Authorize;
  /** Answers counted by route and outcome (`written`, `refused:<why>`, …). */
  counters: Record<
    'calibration' | 'keepOut' | 'import' | 'model' | 'episodes' | 'cameraSegments',
    RouteCounters
  >;
}

type Route = (
  req: http.IncomingMessage,
  res: http.ServerResponse,
  params: Record<string, string | undefined>,
) => unknown;

export function createApi(o: ApiOptions): Api {
  const authorize = createAuthorize(o.auth);
  const may =
    (right: Right): May =>
    async (req) =>
      refusal(o.auth, req, await authorize(req), right);
  const service = serviceRoutes({ auth: o.auth, authorize, service: o.service });
  const robots = { dirs: o.modelDirs, may: may('change'), onFirst: o.onFirst };
  const calibration = calibrationRoute(robots);
  const keepOut = keepOutRoute(robots);
  const robotImport = importRoute({
    modelsDir: o.modelDirs[0] ?? '',
    may: may('change'),
    onFirst: o.onFirst,
  });
  const model = modelCopyRoute({
    copies: o.modelCopies,
    mayDrive: may('change'),
    mayRead: may('view'),
    onFirst: o.onFirst,
  });
  const episodes = episodesRoute({
    service: o.service,
    mayRead: may('data'),
    mayMark: may('change'),
    callerName: async (req) => nameOf(await authorize(req)),
    onFirst: o.onFirst,
  });
  const segments = cameraSegmentsRoute({
    service: o.service,
    mayRead: may('data'),
    onFirst: o.onFirst,
  });

  const router = Router();
  const route = (path: string, r: Route) =>
    router.all(path, r as Router.Handler<Router.HTTPVersion.V1>);
  route('/healthz', service.healthz);
  route('/metrics', service.metrics);
  route('/history', service.history);
  route('/history/*', service.history);
  route('/whoami', service.whoami);
  if (o.modelDirs.length > 0) {
    route('/models/*', modelFiles(o.modelDirs));
    route('/robots/import', robotImport.handle);
    route('/robots/:name/calibration', (req, res, p) => calibration.handle(req, res, p.name!));
    route('/robots/:name/keep-out', (req, res, p) => keepOut.handle(req, res, p.name!));
  }
  route('/arms/:id/episodes', (req, res, p) => episodes.handle(req, res, p.id!));
  route('/arms/:id/cameras/:cam/segments', (req, res, p) =>
    segments.handle(req, res, { id: p.id!, cam: p.cam! }),
  );
  route('/arms/:id/cameras/:cam/segments/:name', (req, res, p) =>
    segments.handle(req, res, { id: p.id!, cam: p.cam!, name: p.name! }),
  );
  route('/arms/:id/model', (req, res, p) => model.handle(req, res, p.id!));

  return {
    authorize,
    counters: {
      calibration: calibration.counters,
      keepOut: keepOut.counters,
      import: robotImport.counters,
      model: model.counters,
      episodes: episodes.counters,
      cameraSegments: segments.counters,
    },
    handle(req, res) {
      const path = (req.url ?? '/').replace(/^\/api(?=[/?]|$)/, '') || '/';
      const found = router.find((req.method ?? 'GET') as Router.HTTPMethod, path);
      if (!found) return false;
      const failed = (err: unknown) => {
        o.onFirst('api', `api request ${req.method} ${path} failed: ${(err as Error).message}`);
        if (!res.headersSent) sendJson(res, 500, { error: 'internal error' });
      };
      try {
        const answered = (found.handler as Route)(req, res, found.params);
        if (answered instanceof Promise) answered.catch(failed);
      } catch (err) {
        failed(err);
      }
      return true;
    },
  };
}
