/**
 * Reads one MJPEG camera stream (packages/camera: `multipart/x-mixed-replace`, one JPEG per
 * part, `X-Timestamp` = the frame's capture time, epoch ms) with the maintained
 * `fetch` and armtwin's own multipart reader (@armtwin/camera/client), until stopped. A frame
 * without `X-Timestamp` is stamped on arrival; one that comes twice (the same `X-Sequence`: a
 * new viewer's first picture can come again live) is passed on once. Node.
 */
import { createMultipartParser, multipartBoundary } from '@armtwin/camera/client';

export interface MjpegHandlers {
  onFrame(jpeg: Uint8Array, ms: number): void;
  /** The stream could not be opened, failed or ended (not called after stop()). */
  onEnd(why: string): void;
}

export interface MjpegReader {
  stop(): void;
}

export function readMjpeg(
  url: string,
  authorization: string | null,
  h: MjpegHandlers,
  now: () => number = Date.now,
): MjpegReader {
  const abort = new AbortController();
  const run = async () => {
    const res = await fetch(url, {
      headers: authorization ? { authorization } : {},
      signal: abort.signal,
    });
    const boundary = multipartBoundary(res.headers.get('content-type'));
    if (res.status !== 200 || !res.body || !boundary) {
      await res.body?.cancel();
      return `the camera answered ${res.status} ${res.statusText}`.trim();
    }
    let lastSeq: string | undefined;
    const parser = createMultipartParser({
      boundary,
      onPart: (p) => {
        const seq = p.headers['x-sequence'];
        if (seq !== undefined && seq === lastSeq) return;
        lastSeq = seq;
        const stamp = Number(p.headers['x-timestamp']);
        h.onFrame(p.body, Number.isFinite(stamp) && stamp > 0 ? stamp : now());
      },
    });
    const reader = res.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) return 'the camera stream ended';
      parser.feed(value);
    }
  };
  run().then(
    (why) => abort.signal.aborted || h.onEnd(why),
    (err: unknown) => abort.signal.aborted || h.onEnd(`camera stream: ${(err as Error).message}`),
  );
  return { stop: () => abort.abort() };
}
