/**
 * The sink-side check of a camera's URL, and the page's credentials for it. The announcement
 * parser already refuses other schemes; this is checked again where the URL is used, so no
 * `javascript:` or `data:` URL ever reaches a `fetch` or a `WebSocket`.
 */
import {
  cameraStreams,
  type CameraAnnouncement,
  type CameraStream,
} from '@armtwin/camera/announcement';

const SCHEMES = { mjpeg: ['http:', 'https:'], 'h264-ws': ['ws:', 'wss:'] } as const;

/** The URL as a URL object when its scheme fits its kind, else null. */
export function usableUrl(s: CameraStream): URL | null {
  let u: URL;
  try {
    u = new URL(s.url);
  } catch {
    return null;
  }
  const schemes: readonly string[] = SCHEMES[s.kind];
  return schemes.includes(u.protocol) && !u.username && !u.password ? u : null;
}

/** The stream this page plays: `h264-ws` where `VideoDecoder` exists, else `mjpeg`. */
export function pickStream(c: CameraAnnouncement, hasDecoder: boolean): CameraStream | null {
  const usable = cameraStreams(c).filter((s) => usableUrl(s) !== null);
  return (
    (hasDecoder ? usable.find((s) => s.kind === 'h264-ws') : undefined) ??
    usable.find((s) => s.kind === 'mjpeg') ??
    null
  );
}

export interface CameraCredentials {
  username: string;
  password: string;
}

/** `name:password` as base64 of its UTF-8 bytes (HTTP Basic, and the camera server's `auth=`). */
export function basicToken(c: CameraCredentials): string {
  let bin = '';
  for (const b of new TextEncoder().encode(`${c.username}:${c.password}`))
    bin += String.fromCharCode(b);
  return btoa(bin);
}

/**
 * A WebSocket cannot send headers: the log-in goes in the `auth=` query parameter
 * (packages/camera/README.md § Access). Unchanged without a log-in.
 */
export function withQueryAuth(u: URL, c: CameraCredentials): URL {
  if (!c.username) return u;
  const out = new URL(u);
  out.searchParams.set('auth', basicToken(c));
  return out;
}
