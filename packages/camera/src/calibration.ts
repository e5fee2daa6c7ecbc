/**
 * A camera's calibration (docs/protocol.md § Cameras), pure and browser-safe: the pose and
 * vertical field of view an operator set by eye or from four clicked points, retained on
 * `arm/{armId}/camera/{camId}/calibration` as `{pose, fovDeg, by, at}` and laid over the
 * announcement's pose by every viewer. Operators write it (the announcement is the camera
 * device's alone); an empty payload clears it. Checked with the announcement's own rules
 * (./announcement.ts): a bad one is rejected with a typed reason, to be ignored and counted.
 */
import { ARM_ID_PATTERN } from '@armtwin/protocol';
import {
  BAD_FOV_MESSAGE,
  BAD_POSE_MESSAGE,
  isFovDeg,
  isValidCamId,
  readJsonObject,
  readPose,
  type AnnouncementRejection,
  type CameraPose,
} from './announcement.ts';

/** Longest `by` (who calibrated) accepted, characters. */
export const MAX_BY_LENGTH = 64;

export interface CameraCalibration {
  pose: CameraPose;
  /** Vertical field of view, degrees. */
  fovDeg: number;
  /** Who set it (the page's user name, or `anonymous`), shown as text. */
  by: string;
  /** When, ISO 8601. */
  at: string;
}

export type CalibrationResult =
  | { type: 'calibration'; calibration: CameraCalibration }
  | { type: 'removed' }
  | { type: 'rejected'; reason: AnnouncementRejection; message: string };

// eslint-disable-next-line no-control-regex
const BY_FORBIDDEN = /[\u0000-\u001f\u007f-\u009f\u202a-\u202e\u2066-\u2069]/;

/** Parses a calibration payload. Never throws; empty = `removed`. */
export function parseCalibration(payload: string | Uint8Array): CalibrationResult {
  const read = readJsonObject(payload, '{pose, fovDeg, by, at}');
  if (read.type !== 'object') return read;
  const o = read.object;
  const pose = readPose(o.pose);
  if (!pose) return { type: 'rejected', reason: 'bad-pose', message: BAD_POSE_MESSAGE };
  if (!isFovDeg(o.fovDeg)) return { type: 'rejected', reason: 'bad-fov', message: BAD_FOV_MESSAGE };
  if (typeof o.by !== 'string' || o.by.length > MAX_BY_LENGTH || BY_FORBIDDEN.test(o.by))
    return {
      type: 'rejected',
      reason: 'bad-calibration',
      message: `by must be a name of at most ${MAX_BY_LENGTH} characters without control characters`,
    };
  if (typeof o.at !== 'string' || o.at.length > 40 || Number.isNaN(Date.parse(o.at)))
    return { type: 'rejected', reason: 'bad-calibration', message: 'at must be an ISO 8601 time' };
  return { type: 'calibration', calibration: { pose, fovDeg: o.fovDeg, by: o.by, at: o.at } };
}

/** The JSON a page publishes (throws a RangeError for what `parseCalibration` would reject). */
export function encodeCalibration(c: CameraCalibration): string {
  const text = JSON.stringify({ pose: c.pose, fovDeg: c.fovDeg, by: c.by, at: c.at });
  const back = parseCalibration(text);
  if (back.type === 'rejected') throw new RangeError(`bad camera calibration: ${back.message}`);
  return text;
}

/** `arm/{armId}/camera/{camId}/calibration`; throws a RangeError for a bad id. */
export function calibrationTopic(armId: string, camId: string): string {
  if (!ARM_ID_PATTERN.test(armId) || !isValidCamId(camId))
    throw new RangeError('invalid camera: ids are [a-z0-9-]{1,32}');
  return `arm/${armId}/camera/${camId}/calibration`;
}

/** The filter for every calibration of one arm's cameras. */
export const calibrationFilter = (armId: string): string => `arm/${armId}/camera/+/calibration`;

/** `arm/{armId}/camera/{camId}/calibration` → ids, or null for any other topic. */
export function parseCalibrationTopic(topic: string): { armId: string; camId: string } | null {
  const parts = topic.split('/');
  if (parts.length !== 5 || parts[0] !== 'arm' || parts[2] !== 'camera') return null;
  if (parts[4] !== 'calibration') return null;
  const armId = parts[1]!;
  const camId = parts[3]!;
  return ARM_ID_PATTERN.test(armId) && isValidCamId(camId) ? { armId, camId } : null;
}
