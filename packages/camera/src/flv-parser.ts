/**
 * Cuts an FLV byte stream (`ffmpeg -f flv pipe:`) into tags, pure: fed chunks of any size, it
 * calls back with each tag the moment its last byte arrives. FLV is how the server reads H.264
 * from ffmpeg because each tag states its length up front: a frame is complete when its bytes are
 * in, where raw Annex B output only ends at the next frame's start code, a frame (33 ms) later.
 *
 * Layout (Adobe FLV v10.1, E.4): a 9-byte header `FLV` 1 flags offset, then
 * `PreviousTagSize0` (u32), then tags: type (u8), data size (u24), time stamp (u24 + u8 upper),
 * stream id (u24), data, and each tag's own size (u32). A stream that breaks this framing
 * cannot be resynchronised safely: the parser reports it once and ignores the rest until
 * `reset()` (the server restarts ffmpeg).
 */
import { ByteBuffer } from './byte-buffer.ts';

export const FLV_ERRORS = ['bad-header', 'bad-tag', 'tag-too-large', 'truncated'] as const;
export type FlvErrorKind = (typeof FLV_ERRORS)[number];

export interface FlvError {
  kind: FlvErrorKind;
  message: string;
}

export const FLV_TAG_AUDIO = 8;
export const FLV_TAG_VIDEO = 9;
export const FLV_TAG_SCRIPT = 18;

export interface FlvTag {
  type: number;
  /** The tag's time stamp, ms (32 bits). */
  timestampMs: number;
  data: Uint8Array;
}

export interface FlvParserOptions {
  onTag: (tag: FlvTag) => void;
  onError?: (error: FlvError) => void;
  /** Largest tag kept, bytes; also the bound on the buffer. */
  maxTagBytes?: number;
}

export const DEFAULT_FLV_PARSER_OPTIONS = { maxTagBytes: 8 << 20 } as const;

export interface FlvParser {
  feed(chunk: Uint8Array): void;
  /** End of stream: reports a tag still incomplete; the next byte starts a new stream. */
  flush(): void;
  reset(): void;
  readonly bufferedBytes: number;
  /** The framing broke: everything is ignored until reset(). */
  readonly failed: boolean;
}

const HEADER_BYTES = 9;
const TAG_HEADER_BYTES = 11;

export function createFlvParser(options: FlvParserOptions): FlvParser {
  const o = { ...DEFAULT_FLV_PARSER_OPTIONS, ...options };
  const buf = new ByteBuffer();
  let state: 'header' | 'tags' | 'failed' = 'header';

  const fail = (kind: FlvErrorKind, message: string) => {
    o.onError?.({ kind, message });
    buf.clear();
    state = 'failed';
  };
  const u24 = (at: number) => (buf.at(at)! << 16) | (buf.at(at + 1)! << 8) | buf.at(at + 2)!;
  const u32 = (at: number) => u24(at) * 256 + buf.at(at + 3)!;

  function step(): boolean {
    if (state === 'header') {
      if (buf.length < HEADER_BYTES) return false;
      const v = buf.view(0, 3);
      if (v[0] !== 0x46 || v[1] !== 0x4c || v[2] !== 0x56 || buf.at(3) !== 1) {
        fail('bad-header', 'not an FLV stream (no "FLV" version 1 header)');
        return false;
      }
      const offset = u32(5);
      if (offset < HEADER_BYTES || offset > 1024) {
        fail('bad-header', `FLV header size ${offset}`);
        return false;
      }
      if (buf.length < offset + 4) return false;
      buf.drop(offset + 4); // the header and PreviousTagSize0
      state = 'tags';
      return true;
    }
    if (state !== 'tags' || buf.length < TAG_HEADER_BYTES) return false;
    const type = buf.at(0)!;
    const size = u24(1);
    if ((type & 0xc0) !== 0 || (type & 0x20) !== 0) {
      fail('bad-tag', `FLV tag type byte ${type}`);
      return false;
    }
    if (size > o.maxTagBytes) {
      fail('tag-too-large', `FLV tag of ${size} bytes, over ${o.maxTagBytes}`);
      return false;
    }
    const total = TAG_HEADER_BYTES + size + 4;
    if (buf.length < total) return false;
    const previous = u32(TAG_HEADER_BYTES + size);
    if (previous !== TAG_HEADER_BYTES + size) {
      fail('bad-tag', `FLV tag size ${previous} after a tag of ${TAG_HEADER_BYTES + size}`);
      return false;
    }
    const timestampMs = ((buf.at(7)! << 24) >>> 0) + u24(4);
    buf.drop(TAG_HEADER_BYTES);
    const data = buf.take(size);
    buf.drop(4);
    o.onTag({ type: type & 0x1f, timestampMs, data });
    return true;
  }

  return {
    feed(chunk) {
      if (state === 'failed') return;
      buf.append(chunk);
      while (step());
    },
    flush() {
      if (state !== 'failed' && buf.length > 0)
        o.onError?.({ kind: 'truncated', message: 'FLV stream cut off inside a tag' });
      buf.clear();
      state = 'header';
    },
    reset() {
      buf.clear();
      state = 'header';
    },
    get bufferedBytes() {
      return buf.length;
    },
    get failed() {
      return state === 'failed';
    },
  };
}
