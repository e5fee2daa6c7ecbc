/**
 * The replay of an MJPEG camera's recorded `.mjpeg` segments (docs/cameras-recording.md): no
 * <video> plays MJPEG, so on each animation frame the replay's instant picks the segment's
 * frame shown then (core/replay/jpegFrames.ts) and an <img> shows it through a `blob:` URL,
 * changed only when the frame changes. Used by ./ReplayVideo.tsx beside its <video>.
 */
import type { RecordedSegment } from '../../../core/replay/videoAt.ts';
import { jpegFrameAt, readJpegFrames, type JpegFrame } from '../../../core/replay/jpegFrames.ts';

export class JpegReplay {
  private name = '';
  private frames: JpegFrame[] | null = null;
  private shown = -1;
  private url = '';

  constructor(
    /** One segment's bytes (fetched whole, with the page's login). */
    private readonly load: (name: string) => Promise<Blob>,
    private readonly onError: (error: string) => void,
  ) {}

  /** Shows in `img` the frame of `segment` at `t` (epoch ms), once the segment is loaded. */
  step(img: HTMLImageElement, segment: RecordedSegment, t: number): void {
    if (segment.name !== this.name) {
      const name = (this.name = segment.name);
      this.frames = null;
      this.shown = -1;
      this.load(name)
        .then((blob) => blob.arrayBuffer())
        .then(
          (bytes) => {
            if (this.name === name) this.frames = readJpegFrames(new Uint8Array(bytes));
          },
          (err: unknown) => this.name === name && this.onError(String(err)),
        );
    }
    if (!this.frames) return;
    const i = jpegFrameAt(this.frames, t);
    if (i < 0 || i === this.shown) return;
    this.shown = i;
    const frame = this.frames[i]!;
    const url = URL.createObjectURL(new Blob([frame.jpeg.slice()], { type: 'image/jpeg' }));
    img.src = url;
    img.dataset.frameAt = String(frame.atMs);
    if (this.url) URL.revokeObjectURL(this.url);
    this.url = url;
  }

  dispose(): void {
    this.name = '';
    if (this.url) URL.revokeObjectURL(this.url);
    this.url = '';
  }
}
