/**
 * An `h264-ws` camera: a WebSocket of H.264 access units (packages/camera/README.md § Kinds) →
 * WebCodecs `VideoDecoder` → the canvas, drawn from the decoder's output callback. At most
 * `maxQueued` frames wait in the decoder; a frame that finds it full is dropped and counted, and
 * so is every frame after it until the next key frame (a delta frame needs the one before it).
 */
import { codecOfAccessUnit, decodeH264Message } from '@armtwin/camera/client';
import { CameraPlayer } from './CameraPlayer.ts';
import { withQueryAuth } from './streamUrl.ts';

/** Whether this page can decode `h264-ws` (WebCodecs exists only in a secure context). */
export const hasVideoDecoder = (): boolean => typeof globalThis.VideoDecoder === 'function';

export class H264Player extends CameraPlayer {
  private ws: WebSocket | null = null;
  private decoder: VideoDecoder | null = null;
  private needKey = true;

  protected open(gen: number): void {
    // Checked again at the sink: only ws(s) is ever opened.
    if (this.url.protocol !== 'ws:' && this.url.protocol !== 'wss:') {
      queueMicrotask(() => this.failed(gen, 'not a ws(s) URL'));
      return;
    }
    this.needKey = true;
    const ws = new WebSocket(withQueryAuth(this.url, this.credentials));
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onmessage = (ev) => {
      if (ev.data instanceof ArrayBuffer) this.onMessage(gen, ev.data);
    };
    ws.onclose = (ev) =>
      this.failed(gen, ev.code === 1000 ? 'the stream ended' : `closed (${ev.code})`);
    ws.onerror = () => this.failed(gen, 'could not connect');
  }

  protected close(): void {
    const ws = this.ws;
    this.ws = null;
    if (ws) {
      ws.onmessage = ws.onclose = ws.onerror = null;
      ws.close();
    }
    const d = this.decoder;
    this.decoder = null;
    if (d && d.state !== 'closed') d.close();
  }

  private onMessage(gen: number, data: ArrayBuffer): void {
    const m = decodeH264Message(data);
    if (!m.ok) {
      this.stats.dropped++;
      return;
    }
    const { key, data: au, timestampMs } = m.message;
    if (!this.decoder && key) {
      const codec = codecOfAccessUnit(au);
      if (!codec) {
        this.stats.dropped++;
        return;
      }
      const decoder = new VideoDecoder({
        output: (frame) => {
          this.drawFrame(gen, frame, frame.displayWidth, frame.displayHeight);
          frame.close();
        },
        error: (e) => this.failed(gen, `decoder: ${e.message}`),
      });
      decoder.configure({ codec, optimizeForLatency: true });
      this.decoder = decoder;
    }
    const decoder = this.decoder;
    if (!decoder || decoder.state !== 'configured') return;
    if (!key && (this.needKey || decoder.decodeQueueSize >= this.opts.maxQueued)) {
      this.needKey = true;
      this.stats.dropped++;
      return;
    }
    this.needKey = false;
    decoder.decode(
      new EncodedVideoChunk({
        type: key ? 'key' : 'delta',
        timestamp: Math.round(timestampMs * 1000),
        data: au,
      }),
    );
  }
}
