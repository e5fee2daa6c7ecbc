/**
 * @armtwin/http-api: armtwin's one HTTP API (./api.ts), served by the middleware and mounted by
 * `armtwin up`. Node only; the answers' types the HUD reads are `@armtwin/api`'s.
 */
export { createApi, type Api, type ApiOptions } from './api.ts';
export {
  createAuthorize,
  hasBearer,
  isLoopback,
  refusal,
  type AuthOptions,
  type Authorize,
  type Caller,
  type Refusal,
  type Right,
} from './authorize.ts';
export type { RouteCounters } from './counted-answer.ts';
export {
  cameraSegmentsRoute,
  type CameraSegment,
  type CameraSegmentService,
} from './camera-segments.ts';
export {
  episodesRoute,
  MAX_EPISODE_REQUEST_BYTES,
  type EpisodeAnswer,
  type EpisodeService,
} from './episodes.ts';
export type { ModelCopyHost } from './model-copies.ts';
export { MAX_MODEL_REQUEST_BYTES, parseModelPose, type ModelPose } from './model-pose.ts';
export { replaceProfileFile } from './robots/profile-file.ts';
export { isFile, readPath, sendFile } from './send-file.ts';
export type { ApiService } from './service-routes.ts';
