/**
 * Viewers of a camera server's streams, as the page watches them: an MJPEG stream read with
 * `@armtwin/camera`'s multipart reader, and an h264-ws stream's messages decoded with its
 * `decodeH264Message`. Each part or message is kept with the time it arrived (`at`).
 */
import WebSocket from 'ws';
import {
  createMultipartParser,
  decodeH264Message,
  multipartBoundary,
  type H264Message,
  type MultipartPart,
} from '@armtwin/camera';

/** Reads an MJPEG stream: parts as they come, until stop(). */
export async function openMjpeg(url: string, authorization?: string) {
  const res = await fetch(url, { headers: authorization ? { authorization } : {} });
  const parts: (MultipartPart & { at: number })[] = [];
  const errors: string[] = [];
  if (res.status !== 200 || !res.body) return { res, parts, errors, stop: async () => {} };
  const parser = createMultipartParser({
    boundary: multipartBoundary(res.headers.get('content-type'))!,
    onPart: (p) => parts.push({ ...p, at: Date.now() }),
    onError: (e) => errors.push(e.kind),
  });
  const reader = res.body.getReader();
  const pump = (async () => {
    for (;;) {
      const r = await reader.read();
      if (r.done) return;
      parser.feed(r.value);
    }
  })().catch(() => {});
  return {
    res,
    parts,
    errors,
    stop: async () => {
      await reader.cancel().catch(() => {});
      await pump;
    },
  };
}

/** Opens an h264-ws stream: messages as they come; `opened` is 101 or the refusal's status. */
export async function openH264(url: string) {
  const ws = new WebSocket(url);
  const messages: (H264Message & { at: number })[] = [];
  ws.on('message', (d: Buffer) => {
    const m = decodeH264Message(new Uint8Array(d));
    if (m.ok) messages.push({ ...m.message, at: Date.now() });
  });
  const opened = await new Promise<number>((resolve, reject) => {
    ws.once('open', () => resolve(101));
    ws.once('unexpected-response', (_req, res) => resolve(res.statusCode ?? 0));
    ws.once('error', reject);
  });
  return { ws, messages, opened, close: () => ws.terminate() };
}
