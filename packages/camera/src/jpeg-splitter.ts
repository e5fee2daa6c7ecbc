/**
 * Cuts a byte stream of concatenated JPEGs (`ffmpeg -f mjpeg pipe:`) into whole images, pure:
 * fed chunks of any size, it calls back with each image from SOI (`FF D8`) to EOI (`FF D9`) the
 * moment its EOI arrives. It walks the marker segments by their lengths and the entropy-coded
 * data by its byte stuffing, so an `FF D9` inside an APP segment (an EXIF thumbnail) does not
 * end the image early. Bounded: an image over `maxFrameBytes` is dropped and reported.
 */
import { ByteBuffer } from './byte-buffer.ts';

export const JPEG_SPLITTER_ERRORS = ['junk', 'bad-marker', 'frame-too-large', 'truncated'] as const;
export type JpegSplitterErrorKind = (typeof JPEG_SPLITTER_ERRORS)[number];

export interface JpegSplitterError {
  kind: JpegSplitterErrorKind;
  message: string;
  /** Bytes dropped. */
  bytes: number;
}

export interface JpegSplitterOptions {
  onFrame: (jpeg: Uint8Array) => void;
  onError?: (error: JpegSplitterError) => void;
  /** Largest image kept, bytes; also the bound on the buffer. */
  maxFrameBytes?: number;
}

export const DEFAULT_JPEG_SPLITTER_OPTIONS = { maxFrameBytes: 8 << 20 } as const;

export interface JpegSplitter {
  feed(chunk: Uint8Array): void;
  /** End of stream: reports a partial image or junk still pending. */
  flush(): void;
  /** Forgets what is pending, reporting nothing. */
  reset(): void;
  readonly bufferedBytes: number;
}

const enum S {
  Seek,
  SeekFF,
  Marker,
  MarkerCode,
  Len1,
  Len2,
  Skip,
  Entropy,
  EntropyFF,
}

const SOI = 0xd8;
const EOI = 0xd9;
const SOS = 0xda;
const standalone = (c: number) => c === 0x01 || (c >= 0xd0 && c <= 0xd7);

export function createJpegSplitter(options: JpegSplitterOptions): JpegSplitter {
  const o = { ...DEFAULT_JPEG_SPLITTER_OPTIONS, ...options };
  const frame = new ByteBuffer();
  let state = S.Seek;
  let marker = 0;
  let length = 0;
  let remaining = 0;
  let junk = 0;
  let dropping = false; // the rest of an over-long image: walked, not kept, up to its EOI

  const report = (kind: JpegSplitterErrorKind, message: string, bytes: number) =>
    o.onError?.({ kind, message, bytes });
  const endJunk = () => {
    if (junk > 0) report('junk', 'bytes outside any JPEG image', junk);
    junk = 0;
  };
  const abandon = (kind: JpegSplitterErrorKind, message: string, extra: number) => {
    report(kind, message, frame.length + extra);
    frame.clear();
    state = S.Seek;
  };

  function feed(chunk: Uint8Array): void {
    let from = 0; // start of the bytes of `chunk` that belong to the current image
    let i = 0;
    const keep = (to: number) => {
      if (dropping) return;
      if (frame.length + (to - from) > o.maxFrameBytes) {
        // Dropped, but still walked to its end, so the next image is found cleanly.
        report('frame-too-large', `image over ${o.maxFrameBytes} bytes`, frame.length + to - from);
        frame.clear();
        dropping = true;
        return;
      }
      frame.append(chunk.subarray(from, to));
    };
    while (i < chunk.length) {
      const c = chunk[i]!;
      switch (state) {
        case S.Seek: {
          const ff = chunk.indexOf(0xff, i);
          junk += (ff < 0 ? chunk.length : ff) - i;
          if (ff < 0) return;
          i = ff + 1;
          state = S.SeekFF;
          continue;
        }
        case S.SeekFF:
          if (c === SOI) {
            endJunk();
            frame.clear();
            frame.append(new Uint8Array([0xff, SOI]));
            from = i + 1;
            state = S.Marker;
          } else if (c !== 0xff) {
            junk += 2;
            state = S.Seek;
          } else junk++;
          i++;
          continue;
        case S.Marker:
          if (c !== 0xff) {
            if (!dropping) abandon('bad-marker', `byte ${c} where a JPEG marker belongs`, i - from);
            dropping = false;
            state = S.Seek;
            continue; // look at this byte again
          }
          state = S.MarkerCode;
          i++;
          continue;
        case S.MarkerCode:
          i++;
          if (c === 0xff) continue;
          marker = c;
          if (c === EOI) {
            keep(i);
            if (!dropping) o.onFrame(frame.take(frame.length));
            dropping = false;
            state = S.Seek;
            from = i;
          } else if (c === SOI) {
            if (!dropping) abandon('truncated', 'JPEG image without its end (EOI)', i - from);
            dropping = false;
            frame.clear();
            frame.append(new Uint8Array([0xff, SOI]));
            from = i;
            state = S.Marker;
          } else state = standalone(c) ? S.Marker : S.Len1;
          continue;
        case S.Len1:
          length = c << 8;
          state = S.Len2;
          i++;
          continue;
        case S.Len2:
          length |= c;
          i++;
          if (length < 2) {
            if (!dropping) abandon('bad-marker', `JPEG segment length ${length}`, i - from);
            dropping = false;
            state = S.Seek;
            continue;
          }
          remaining = length - 2;
          state = remaining > 0 ? S.Skip : marker === SOS ? S.Entropy : S.Marker;
          continue;
        case S.Skip: {
          const n = Math.min(remaining, chunk.length - i);
          remaining -= n;
          i += n;
          if (remaining === 0) state = marker === SOS ? S.Entropy : S.Marker;
          continue;
        }
        case S.Entropy: {
          const ff = chunk.indexOf(0xff, i);
          if (ff < 0) {
            i = chunk.length;
            continue;
          }
          i = ff + 1;
          state = S.EntropyFF;
          continue;
        }
        case S.EntropyFF:
          if (c === 0x00 || (c >= 0xd0 && c <= 0xd7)) {
            state = S.Entropy;
            i++;
          } else if (c === 0xff) i++;
          else state = S.MarkerCode; // a marker after the scan: EOI, or DHT/SOS of the next scan
          continue;
      }
    }
    if (state !== S.Seek && state !== S.SeekFF) keep(chunk.length);
  }

  return {
    feed,
    flush() {
      if (frame.length > 0 && !dropping) abandon('truncated', 'JPEG image cut off at the end', 0);
      if (state === S.SeekFF) junk++;
      endJunk();
      dropping = false;
      frame.clear();
      state = S.Seek;
    },
    reset() {
      frame.clear();
      junk = 0;
      dropping = false;
      state = S.Seek;
    },
    get bufferedBytes() {
      return frame.length;
    },
  };
}
