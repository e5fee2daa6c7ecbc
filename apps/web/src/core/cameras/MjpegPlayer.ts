/**
 * An `mjpeg` camera (multipart/x-mixed-replace over HTTP(S)) read with `fetch` and the camera
 * package's multipart reader, each JPEG decoded with `createImageBitmap` and drawn into the
 * canvas. Not an `<img>`: an `<img>` says neither when a frame came nor when the stream ended,
 * and cannot send the log-in in a header. One JPEG decodes at a time; of those that come
 * meanwhile only the newest waits, the others are dropped and counted.
 */
import { createMultipartParser, multipartBoundary } from '@armtwin/camera/client';
import { CameraPlayer } from './CameraPlayer.ts';
import { basicToken } from './streamUrl.ts';

export class MjpegPlayer extends CameraPlayer {
  private abort: AbortController | null = null;
  private decoding = false;
  private pending: Uint8Array<ArrayBuffer> | null = null;

  protected open(gen: number): void {
    const abort = new AbortController();
    this.abort = abort;
    this.read(gen, abort.signal).catch((err: unknown) => {
      this.failed(gen, err instanceof Error ? err.message : String(err));
    });
  }

  protected close(): void {
    this.abort?.abort();
    this.abort = null;
    this.pending = null;
  }

  private async read(gen: number, signal: AbortSignal): Promise<void> {
    // Checked again at the sink: only http(s) is ever fetched.
    if (this.url.protocol !== 'http:' && this.url.protocol !== 'https:')
      throw new Error(`not an http(s) URL`);
    const headers: Record<string, string> = {};
    if (this.credentials.username) headers.authorization = `Basic ${basicToken(this.credentials)}`;
    const res = await fetch(this.url, { headers, signal, cache: 'no-store', credentials: 'omit' });
    if (!res.ok || !res.body) throw new Error(`HTTP ${res.status}`);
    const boundary = multipartBoundary(res.headers.get('content-type'));
    if (!boundary) throw new Error('not a multipart stream');
    const parser = createMultipartParser({
      boundary,
      onPart: (p) => this.take(gen, p.body),
      onError: () => this.stats.dropped++,
    });
    const reader = res.body.getReader();
    for (;;) {
      const { done, value } = await reader.read();
      if (done) break;
      parser.feed(value);
    }
    throw new Error('the stream ended');
  }

  private take(gen: number, jpeg: Uint8Array): void {
    if (gen !== this.generation) return;
    if (this.decoding) {
      if (this.pending) this.stats.dropped++;
      this.pending = jpeg.slice();
      return;
    }
    this.decode(gen, new Blob([jpeg.slice()], { type: 'image/jpeg' }));
  }

  private decode(gen: number, blob: Blob): void {
    this.decoding = true;
    createImageBitmap(blob)
      .then((bmp) => {
        this.drawFrame(gen, bmp, bmp.width, bmp.height);
        bmp.close();
      })
      .catch(() => this.stats.dropped++)
      .finally(() => {
        this.decoding = false;
        const next = this.pending;
        this.pending = null;
        if (next && gen === this.generation)
          this.decode(gen, new Blob([next], { type: 'image/jpeg' }));
      });
  }
}
