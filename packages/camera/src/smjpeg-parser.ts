/**
 * JPEGs and their time stamps out of an SMJPEG byte stream (`ffmpeg -f smjpeg pipe:`), pure:
 * fed chunks of any size, it calls back with each JPEG the moment its last byte arrives. SMJPEG
 * is how the server reads MJPEG from ffmpeg because, unlike bare JPEGs (`-f mjpeg`), each frame
 * carries its time (ms, 32 bits: ./capture-time.ts) and states its length up front.
 *
 * Layout (Loki's SMJPEG 0, as ffmpeg's `smjpegenc.c` writes it; big-endian): the magic
 * `00 0A "SMJPEG"`, version (u32), duration (u32), then header chunks, each a four-letter tag
 * and a u32 length before its bytes (`_TXT` metadata, `_VID`, `_SND`), up to `HEND`; then frames,
 * each `vidD` (or `sndD`), time stamp ms (u32), size (u32), data; `DONE` at the end. A stream
 * that breaks this framing is reported once and ignored until `reset()` (the server restarts
 * ffmpeg).
 */
import { ByteBuffer } from './byte-buffer.ts';

export const SMJPEG_ERRORS = ['bad-header', 'bad-chunk', 'frame-too-large', 'truncated'] as const;
export type SmjpegErrorKind = (typeof SMJPEG_ERRORS)[number];

export interface SmjpegError {
  kind: SmjpegErrorKind;
  message: string;
}

export interface SmjpegFrame {
  jpeg: Uint8Array;
  /** The frame's time stamp, ms (the low 32 bits of ffmpeg's pts). */
  timestampMs: number;
}

export interface SmjpegParserOptions {
  onFrame: (frame: SmjpegFrame) => void;
  onError?: (error: SmjpegError) => void;
  /** Largest frame or header chunk kept, bytes; also the bound on the buffer. */
  maxFrameBytes?: number;
}

export const DEFAULT_SMJPEG_PARSER_OPTIONS = { maxFrameBytes: 8 << 20 } as const;

export interface SmjpegParser {
  feed(chunk: Uint8Array): void;
  /** End of stream: reports a frame still incomplete; the next byte starts a new stream. */
  flush(): void;
  reset(): void;
  readonly bufferedBytes: number;
  /** The framing broke: everything is ignored until reset(). */
  readonly failed: boolean;
}

const MAGIC = [0x00, 0x0a, 0x53, 0x4d, 0x4a, 0x50, 0x45, 0x47]; // \0 \n SMJPEG
const PREAMBLE_BYTES = 16; // magic, version, duration
const HEADER_TAGS = new Set(['_TXT', '_VID', '_SND']);

export function createSmjpegParser(options: SmjpegParserOptions): SmjpegParser {
  const o = { ...DEFAULT_SMJPEG_PARSER_OPTIONS, ...options };
  const buf = new ByteBuffer();
  let state: 'preamble' | 'header' | 'frames' | 'done' | 'failed' = 'preamble';

  const fail = (kind: SmjpegErrorKind, message: string) => {
    o.onError?.({ kind, message });
    buf.clear();
    state = 'failed';
  };
  const u32 = (at: number) =>
    buf.at(at)! * 2 ** 24 + ((buf.at(at + 1)! << 16) | (buf.at(at + 2)! << 8) | buf.at(at + 3)!);
  const tag = () => String.fromCharCode(...buf.view(0, 4));
  const tooLarge = (size: number, what: string) => {
    if (size <= o.maxFrameBytes) return false;
    fail('frame-too-large', `SMJPEG ${what} of ${size} bytes, over ${o.maxFrameBytes}`);
    return true;
  };

  function step(): boolean {
    if (state === 'preamble') {
      if (buf.length < PREAMBLE_BYTES) return false;
      if (MAGIC.some((b, i) => buf.at(i) !== b)) {
        fail('bad-header', 'not an SMJPEG stream (no "\\0\\nSMJPEG" magic)');
        return false;
      }
      buf.drop(PREAMBLE_BYTES);
      state = 'header';
      return true;
    }
    if (state === 'header') {
      if (buf.length < 4) return false;
      const t = tag();
      if (t === 'HEND') {
        buf.drop(4);
        state = 'frames';
        return true;
      }
      if (!HEADER_TAGS.has(t)) {
        fail('bad-header', `SMJPEG header chunk ${JSON.stringify(t)}`);
        return false;
      }
      if (buf.length < 8) return false;
      const size = u32(4);
      if (tooLarge(size, `${t} chunk`) || buf.length < 8 + size) return false;
      buf.drop(8 + size);
      return true;
    }
    if (state !== 'frames' || buf.length < 4) return false;
    const t = tag();
    if (t === 'DONE') {
      buf.drop(4);
      state = 'done';
      return false;
    }
    if (t !== 'vidD' && t !== 'sndD') {
      fail('bad-chunk', `SMJPEG chunk ${JSON.stringify(t)}`);
      return false;
    }
    if (buf.length < 12) return false;
    const size = u32(8);
    if (tooLarge(size, 'frame') || buf.length < 12 + size) return false;
    const timestampMs = u32(4);
    buf.drop(12);
    const data = buf.take(size);
    if (t === 'vidD') o.onFrame({ jpeg: data, timestampMs });
    return true;
  }

  return {
    feed(chunk) {
      if (state === 'failed' || state === 'done') return;
      buf.append(chunk);
      while (step());
    },
    flush() {
      if (state !== 'failed' && state !== 'done' && buf.length > 0)
        o.onError?.({ kind: 'truncated', message: 'SMJPEG stream cut off inside a chunk' });
      buf.clear();
      state = 'preamble';
    },
    reset() {
      buf.clear();
      state = 'preamble';
    },
    get bufferedBytes() {
      return buf.length;
    },
    get failed() {
      return state === 'failed';
    },
  };
}
