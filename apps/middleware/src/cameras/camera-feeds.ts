/**
 * The two ways a recorder watches a camera, as any viewer does: an `h264-ws` WebSocket (one
 * access unit per message behind its header, `@armtwin/camera`'s wire) or an MJPEG
 * `multipart/x-mixed-replace` response read with fetch (one JPEG per part). Each frame is handed
 * on with its time: the `h264-ws` header's; for MJPEG the part's `X-Timestamp` (armtwin's camera
 * server stamps each frame with its capture time, epoch ms) when it is epoch ms within
 * `MAX_STAMP_SKEW_MS` of the clock (`@armtwin/camera`'s `wallClockStamp`), else the time it
 * arrived (other cameras' stamps, ustreamer's monotonic seconds for one, are no epoch ms).
 */
import tls from 'node:tls';
import { WebSocket } from 'ws';
import {
  createMultipartParser,
  decodeH264Message,
  multipartBoundary,
  wallClockStamp,
} from '@armtwin/camera';

export interface FeedHandlers {
  /** The connection is open. */
  open(): void;
  frame(data: Uint8Array, key: boolean, atMs: number): void;
  problem(kind: string, message: string): void;
  /** Counted events (`frame-times-arrival`). */
  event(kind: string): void;
  /** The feed ended (dropped, refused, or closed): called once. */
  closed(): void;
}

export interface Feed {
  close(): void;
}

/**
 * `ca`: a certificate trusted besides Node's roots (`armtwin up`'s own, perhaps self-signed, for
 * its own camera server). The MJPEG feed has no such option: Node 20's fetch takes no CA of its
 * own (that needs undici's Agent), and `armtwin up`'s camera is recorded through its H.264 stream.
 */
export function openH264Feed(
  url: string,
  authorization: string,
  h: FeedHandlers,
  ca?: Buffer,
): Feed {
  const headers = authorization ? { authorization } : undefined;
  const trust = ca ? { ca: [...tls.rootCertificates, ca.toString()] } : {};
  const ws = new WebSocket(url, { headers, perMessageDeflate: false, ...trust });
  ws.binaryType = 'nodebuffer';
  ws.on('open', () => h.open());
  ws.on('message', (data: Buffer, binary) => {
    if (!binary) return;
    const m = decodeH264Message(data);
    if (!m.ok) return h.problem(`wire-${m.error}`, `bad h264-ws message: ${m.error}`);
    h.frame(m.message.data, m.message.key, m.message.timestampMs);
  });
  ws.on('error', (err) => h.problem('connect-failed', `${url}: ${err.message}`));
  ws.on('close', () => h.closed());
  return { close: () => ws.terminate() };
}

/** The frame's time from its part's `X-Timestamp`, or the arrival time `nowMs`. */
export function partTime(stamp: string | undefined, nowMs: number): number | null {
  const at = stamp !== undefined && /^\d{1,16}(\.\d+)?$/.test(stamp) ? Number(stamp) : NaN;
  return wallClockStamp(at, nowMs);
}

export function openMjpegFeed(
  url: string,
  authorization: string,
  h: FeedHandlers,
  now: () => number,
): Feed {
  const abort = new AbortController();
  let done = false;
  const closed = () => {
    if (done) return;
    done = true;
    h.closed();
  };
  void (async () => {
    const res = await fetch(url, {
      headers: authorization ? { authorization } : {},
      signal: abort.signal,
    });
    const boundary = multipartBoundary(res.headers.get('content-type'));
    if (!res.ok || !boundary || !res.body) {
      await res.body?.cancel();
      throw new Error(`${res.status} ${res.headers.get('content-type') ?? ''}`.trim());
    }
    h.open();
    const parser = createMultipartParser({
      boundary,
      onPart: ({ headers, body }) => {
        const t = now();
        const stamped = partTime(headers['x-timestamp'], t);
        if (stamped === null) h.event('frame-times-arrival');
        h.frame(body, true, stamped ?? t);
      },
      onError: (e) => h.problem(`multipart-${e.kind}`, `${url}: ${e.message}`),
    });
    const reader = res.body.getReader();
    for (let r = await reader.read(); !r.done; r = await reader.read()) parser.feed(r.value);
  })()
    .catch((err: Error) => {
      if (!abort.signal.aborted) h.problem('connect-failed', `${url}: ${err.message}`);
    })
    .finally(closed);
  return { close: () => abort.abort() };
}
