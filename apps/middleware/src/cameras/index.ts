/**
 * Camera recording (docs/cameras-recording.md): the middleware records every announced camera's
 * H.264 stream as it is served, in MP4 segments beside the history.
 */
import type { Logger } from 'pino';
import type { MiddlewareConfig } from '../config.ts';
import { Recordings } from './recordings.ts';

export { Recordings, DEFAULT_RECORDINGS_OPTIONS, type RecordingsOptions } from './recordings.ts';
export { RecordingCounters } from './recording-counters.ts';
export {
  parseSegmentName,
  segmentKind,
  segmentName,
  segmentsBetween,
  retentionPlan,
  type Segment,
} from './segment-files.ts';
export { Takes } from './takes.ts';
export { readCameraFolder, readCameraFolders, type CameraFolder } from './segment-folder.ts';
export { segmenterArgs } from './segmenter.ts';

/** The camera announcements the recording follows (PROTOCOL.md §7). */
export const CAMERA_FILTER = 'arm/+/camera/+';

/**
 * The recordings of a middleware: its MQTT log-in (HTTP Basic) opens the camera servers, whose
 * access lets the middleware role watch every arm's cameras; without one, `fallback` (the
 * token `armtwin up` mints for its in-process middleware), if any.
 */
export function startRecordings(
  config: MiddlewareConfig,
  log: Logger,
  now: () => number,
  fallback = '',
  ca?: Buffer,
) {
  const authorization = config.mqttUsername
    ? `Basic ${Buffer.from(`${config.mqttUsername}:${config.mqttPassword}`).toString('base64')}`
    : fallback;
  const recordings = new Recordings({
    dir: config.cameraDir,
    ffmpeg: config.ffmpeg,
    segmentS: config.cameraSegmentS,
    maxAgeMs: config.cameraRetentionHours * 3_600_000,
    maxBytes: config.cameraRetentionBytes,
    authorization,
    ...(ca ? { ca } : {}),
    now,
    onFirst: (kind, message) =>
      log.warn({ kind }, `camera recording: ${message} (logged once per kind)`),
  });
  log.info(
    {
      dir: config.cameraDir,
      segmentS: config.cameraSegmentS,
      retentionHours: config.cameraRetentionHours,
      retentionBytes: config.cameraRetentionBytes,
    },
    'camera recording: every announced camera',
  );
  return recordings;
}
