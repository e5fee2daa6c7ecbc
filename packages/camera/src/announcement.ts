/**
 * The camera contract of PROTOCOL.md §7, pure and browser-safe (the HUD imports it as
 * `@armtwin/camera/announcement`): the topic `arm/{armId}/camera/{camId}`, and its retained JSON
 * payload `{url, kind, label, pose?, fovDeg?}`. An empty payload removes the camera; unknown
 * fields are ignored; anything else is rejected with a typed reason, so a consumer counts it.
 *
 * armtwin's own extension (an unknown field to any other §7 reader): `alternates`, the same
 * picture in other kinds, e.g. `[{url: 'ws://…/camera/front.h264', kind: 'h264-ws'}]`; a viewer
 * plays the first of `streams` (the main one, then the alternates) that it can.
 */
import { z } from 'zod';
import { ARM_ID_PATTERN } from '@armtwin/protocol';

/**
 * The stream kinds armtwin plays:
 * - `mjpeg`: `multipart/x-mixed-replace` over HTTP(S), one JPEG per part (IP cameras, ustreamer,
 *   mjpg-streamer, `ffmpeg -f mpjpeg`, and this package's server);
 * - `h264-ws`: H.264 access units in Annex B over a WebSocket, one binary message each behind
 *   a 16-byte header (./wire.ts), for WebCodecs `VideoDecoder` (`avc1.42C01E`).
 */
export const CAMERA_KINDS = ['mjpeg', 'h264-ws'] as const;
export type CameraKind = (typeof CAMERA_KINDS)[number];

/** camId: `[a-z0-9-]{1,32}`, like an arm id. */
export const CAM_ID_PATTERN = /^[a-z0-9-]{1,32}$/;
/** Largest announcement payload accepted, bytes. */
export const MAX_ANNOUNCEMENT_BYTES = 4096;
/** Longest URL accepted, characters. */
export const MAX_URL_LENGTH = 2048;
/** Longest label accepted, characters (UTF-16 code units). */
export const MAX_LABEL_LENGTH = 80;
/** Largest |coordinate| of a pose, mm. */
export const MAX_POSE_MM = 100_000;
/** Most alternates accepted. */
export const MAX_ALTERNATES = 4;

/** Why a payload was not taken as a camera; one counter per reason. */
export const ANNOUNCEMENT_REJECTIONS = [
  'bad-topic',
  'too-large',
  'not-json',
  'not-object',
  'bad-url',
  'unsupported-url',
  'url-credentials',
  'unsupported-kind',
  'url-kind-mismatch',
  'bad-label',
  'bad-pose',
  'bad-fov',
  'bad-alternates',
  // A calibration (./calibration.ts) whose `by` or `at` is not what it must be.
  'bad-calibration',
] as const;
export type AnnouncementRejection = (typeof ANNOUNCEMENT_REJECTIONS)[number];

/** The URL schemes a kind is read over. */
export const KIND_SCHEMES: Record<CameraKind, readonly string[]> = {
  mjpeg: ['http:', 'https:'],
  'h264-ws': ['ws:', 'wss:'],
};
const ALL_SCHEMES: ReadonlySet<string> = new Set(['http:', 'https:', 'ws:', 'wss:']);

export type Vec3 = [number, number, number];

/** Where the camera is, in mm in the arm's frame (§4), and the point it looks at. */
export interface CameraPose {
  position: Vec3;
  lookAt: Vec3;
}

export interface CameraStream {
  url: string;
  kind: CameraKind;
}

export interface CameraAnnouncement extends CameraStream {
  label: string;
  pose?: CameraPose;
  /** Vertical field of view, degrees. */
  fovDeg?: number;
  /** The same picture in other kinds (armtwin's extension); empty when there are none. */
  alternates: CameraStream[];
}

export type AnnouncementResult =
  | { type: 'camera'; camera: CameraAnnouncement }
  | { type: 'removed' }
  | { type: 'rejected'; reason: AnnouncementRejection; message: string };

const coordinate = z.number().min(-MAX_POSE_MM).max(MAX_POSE_MM);
const vec3 = z.tuple([coordinate, coordinate, coordinate]);
const POSE = z.object({ position: vec3, lookAt: vec3 });
const STREAM = z.object({ url: z.string(), kind: z.string() });
/** Any JSON object: each field is checked on its own below, for a reason of its own. */
const SHAPE = z.record(z.string(), z.unknown());

/** C0 and C1 controls, and the bidirectional overrides and isolates that can disguise a label. */
// eslint-disable-next-line no-control-regex
const LABEL_FORBIDDEN = /[\u0000-\u001f\u007f-\u009f\u202a-\u202e\u2066-\u2069]/;

const reject = (reason: AnnouncementRejection, message: string): AnnouncementResult => ({
  type: 'rejected',
  reason,
  message,
});

const isKind = (k: unknown): k is CameraKind => CAMERA_KINDS.includes(k as CameraKind);

/** Checks one `{url, kind}`: a rejection, or null when it may be used. */
function checkStream(url: unknown, kind: unknown): AnnouncementResult | null {
  if (typeof url !== 'string' || url.length === 0 || url.length > MAX_URL_LENGTH)
    return reject('bad-url', `url must be a string of 1–${MAX_URL_LENGTH} characters`);
  let parsed: URL;
  try {
    parsed = new URL(url);
  } catch {
    return reject('bad-url', 'url is not an absolute URL');
  }
  if (!ALL_SCHEMES.has(parsed.protocol))
    return reject(
      'unsupported-url',
      `only http, https, ws and wss URLs are used, not ${parsed.protocol}`,
    );
  if (parsed.username || parsed.password)
    return reject('url-credentials', 'a retained url must not carry a user name or password');
  if (!isKind(kind))
    return reject('unsupported-kind', `kind must be one of ${CAMERA_KINDS.join(', ')}`);
  if (!KIND_SCHEMES[kind].includes(parsed.protocol))
    return reject(
      'url-kind-mismatch',
      `a ${kind} stream is read over ${KIND_SCHEMES[kind].join(' or ')}`,
    );
  return null;
}

function checkLabel(label: unknown): string | null {
  if (typeof label !== 'string' || label.trim().length === 0 || label.length > MAX_LABEL_LENGTH)
    return `label must be a non-blank string of at most ${MAX_LABEL_LENGTH} characters`;
  if (LABEL_FORBIDDEN.test(label)) return 'label must not hold control or bidi-override characters';
  return null;
}

/** Same point, or no direction to look in. */
const degenerate = (p: CameraPose) => p.position.every((v, i) => v === p.lookAt[i]);

/** A payload read as a JSON object, or why not (shared with ./calibration.ts). */
export type JsonObjectResult =
  | { type: 'object'; object: Record<string, unknown> }
  | { type: 'removed' }
  | { type: 'rejected'; reason: AnnouncementRejection; message: string };

/**
 * The first checks of every camera payload: empty = removed; at most `MAX_ANNOUNCEMENT_BYTES`;
 * UTF-8 JSON; an object (`what` names its fields in the message).
 */
export function readJsonObject(payload: string | Uint8Array, what: string): JsonObjectResult {
  if (payload.length === 0) return { type: 'removed' };
  // UTF-8 never takes fewer bytes than UTF-16 code units, so a long string is too large at once.
  const size =
    typeof payload !== 'string'
      ? payload.length
      : payload.length > MAX_ANNOUNCEMENT_BYTES
        ? payload.length
        : new TextEncoder().encode(payload).length;
  if (size > MAX_ANNOUNCEMENT_BYTES)
    return {
      type: 'rejected',
      reason: 'too-large',
      message: `payload is over ${MAX_ANNOUNCEMENT_BYTES} bytes`,
    };
  let json: unknown;
  try {
    const text =
      typeof payload === 'string'
        ? payload
        : new TextDecoder('utf-8', { fatal: true }).decode(payload);
    json = JSON.parse(text);
  } catch {
    return { type: 'rejected', reason: 'not-json', message: 'payload is not UTF-8 JSON' };
  }
  const shape = SHAPE.safeParse(json);
  if (!shape.success || Array.isArray(json))
    return {
      type: 'rejected',
      reason: 'not-object',
      message: `payload must be a JSON object ${what}`,
    };
  return { type: 'object', object: shape.data };
}

/** A §7 `pose`, or null when it is not one (two different points, |v| ≤ MAX_POSE_MM). */
export function readPose(v: unknown): CameraPose | null {
  const pose = POSE.safeParse(v);
  if (!pose.success || degenerate(pose.data)) return null;
  return { position: pose.data.position, lookAt: pose.data.lookAt };
}
export const BAD_POSE_MESSAGE = `pose must be {position: [x, y, z], lookAt: [x, y, z]} in mm (|v| ≤ ${MAX_POSE_MM}), two different points`;

/** A §7 `fovDeg`: a number of degrees strictly between 0 and 180. */
export const isFovDeg = (v: unknown): v is number => typeof v === 'number' && v > 0 && v < 180;
export const BAD_FOV_MESSAGE = 'fovDeg must be a number of degrees between 0 and 180';

/**
 * Parses the retained payload of `arm/{armId}/camera/{camId}`. Never throws. Text or bytes
 * (UTF-8); an empty payload is `removed`.
 */
export function parseAnnouncement(payload: string | Uint8Array): AnnouncementResult {
  const read = readJsonObject(payload, '{url, kind, label, …}');
  if (read.type !== 'object') return read;
  const o = read.object;
  const streamProblem = checkStream(o.url, o.kind);
  if (streamProblem) return streamProblem;
  const labelProblem = checkLabel(o.label);
  if (labelProblem) return reject('bad-label', labelProblem);
  const camera: CameraAnnouncement = {
    url: o.url as string,
    kind: o.kind as CameraKind,
    label: o.label as string,
    alternates: [],
  };
  if (o.pose !== undefined) {
    const pose = readPose(o.pose);
    if (!pose) return reject('bad-pose', BAD_POSE_MESSAGE);
    camera.pose = pose;
  }
  if (o.fovDeg !== undefined) {
    if (!isFovDeg(o.fovDeg)) return reject('bad-fov', BAD_FOV_MESSAGE);
    camera.fovDeg = o.fovDeg;
  }
  if (o.alternates !== undefined) {
    const list = z.array(STREAM).max(MAX_ALTERNATES).safeParse(o.alternates);
    if (!list.success)
      return reject('bad-alternates', `alternates must be at most ${MAX_ALTERNATES} {url, kind}`);
    for (const s of list.data) {
      const problem = checkStream(s.url, s.kind);
      if (problem?.type === 'rejected')
        return reject('bad-alternates', `an alternate is unusable: ${problem.message}`);
      camera.alternates.push({ url: s.url, kind: s.kind as CameraKind });
    }
  }
  return { type: 'camera', camera };
}

/** The main stream, then the alternates: a viewer plays the first it can. */
export const cameraStreams = (c: CameraAnnouncement): CameraStream[] => [
  { url: c.url, kind: c.kind },
  ...c.alternates,
];

/** The JSON an announcer publishes (checked: throws a RangeError for what parse would reject). */
export function encodeAnnouncement(c: CameraAnnouncement): string {
  const text = JSON.stringify({
    url: c.url,
    kind: c.kind,
    label: c.label,
    ...(c.pose ? { pose: c.pose } : {}),
    ...(c.fovDeg !== undefined ? { fovDeg: c.fovDeg } : {}),
    ...(c.alternates.length ? { alternates: c.alternates } : {}),
  });
  const back = parseAnnouncement(text);
  if (back.type === 'rejected') throw new RangeError(`bad camera announcement: ${back.message}`);
  return text;
}

export const isValidCamId = (camId: string): boolean => CAM_ID_PATTERN.test(camId);

/** `arm/{armId}/camera/{camId}`; throws a RangeError for a bad id. */
export function cameraTopic(armId: string, camId: string): string {
  if (!ARM_ID_PATTERN.test(armId) || !isValidCamId(camId))
    throw new RangeError(
      `invalid camera ${JSON.stringify(`${armId}/${camId}`).slice(0, 80)}: ids are [a-z0-9-]{1,32}`,
    );
  return `arm/${armId}/camera/${camId}`;
}

/** The filter that matches every camera of one arm (`+`: every arm). */
export const cameraFilter = (armId: string): string => `arm/${armId}/camera/+`;

/** `arm/{armId}/camera/{camId}` → ids, or null for any other topic. */
export function parseCameraTopic(topic: string): { armId: string; camId: string } | null {
  const parts = topic.split('/');
  if (parts.length !== 4 || parts[0] !== 'arm' || parts[2] !== 'camera') return null;
  const [, armId, , camId] = parts as [string, string, string, string];
  return ARM_ID_PATTERN.test(armId) && isValidCamId(camId) ? { armId, camId } : null;
}

/** A message on a camera topic, in one call: the ids and what the payload says. */
export type CameraMessage =
  | (AnnouncementResult & { armId: string; camId: string })
  | { type: 'rejected'; reason: 'bad-topic'; message: string };

export function parseCameraMessage(topic: string, payload: string | Uint8Array): CameraMessage {
  const ids = parseCameraTopic(topic);
  if (!ids)
    return {
      type: 'rejected',
      reason: 'bad-topic',
      message: 'not arm/{armId}/camera/{camId} with ids [a-z0-9-]{1,32}',
    };
  return { ...parseAnnouncement(payload), ...ids };
}
