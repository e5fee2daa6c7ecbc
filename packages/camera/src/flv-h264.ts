/**
 * H.264 access units out of ffmpeg's FLV output, pure: each video tag is one access unit in AVCC
 * form (length-prefixed NAL units); the first tag is the decoder configuration (SPS and PPS).
 * They come out in Annex B (start codes), key frames with the SPS and PPS in front, so every key
 * frame can start a decoder on its own — what a WebCodecs `VideoDecoder` without a `description`
 * and a newly arrived viewer both need.
 */
import { createFlvParser, FLV_TAG_VIDEO, type FlvErrorKind } from './flv-parser.ts';

export const FLV_H264_ERRORS = ['not-h264', 'bad-config', 'no-config', 'bad-nal-length'] as const;
export type FlvH264ErrorKind = FlvErrorKind | (typeof FLV_H264_ERRORS)[number];

export interface FlvH264Error {
  kind: FlvH264ErrorKind;
  message: string;
}

export interface AccessUnit {
  /** Annex B. */
  data: Uint8Array;
  key: boolean;
  /** The FLV time stamp, ms. */
  timestampMs: number;
}

export interface AvcConfig {
  sps: Uint8Array[];
  pps: Uint8Array[];
  /** Bytes of each NAL unit's length prefix, 1, 2 or 4. */
  lengthSize: number;
}

export interface FlvH264ReaderOptions {
  onAccessUnit: (au: AccessUnit) => void;
  onError?: (error: FlvH264Error) => void;
  maxTagBytes?: number;
}

export interface FlvH264Reader {
  feed(chunk: Uint8Array): void;
  flush(): void;
  /** A new stream (ffmpeg restarted): forgets the configuration too. */
  reset(): void;
  readonly config: AvcConfig | null;
}

const START_CODE = new Uint8Array([0, 0, 0, 1]);

/** An AVCDecoderConfigurationRecord (ISO/IEC 14496-15 5.2.4.1) → SPS, PPS, length size. */
export function parseAvcConfig(d: Uint8Array): AvcConfig | null {
  if (d.length < 7 || d[0] !== 1) return null;
  const lengthSize = (d[4]! & 0x03) + 1;
  if (lengthSize === 3) return null;
  let at = 5;
  const list = (count: number): Uint8Array[] | null => {
    const out: Uint8Array[] = [];
    for (let k = 0; k < count; k++) {
      if (at + 2 > d.length) return null;
      const n = (d[at]! << 8) | d[at + 1]!;
      at += 2;
      if (n === 0 || at + n > d.length) return null;
      out.push(d.slice(at, at + n));
      at += n;
    }
    return out;
  };
  const sps = list(d[at++]! & 0x1f);
  if (!sps || at >= d.length) return null;
  const pps = list(d[at++]!);
  if (!pps || sps.length === 0 || pps.length === 0) return null;
  return { sps, pps, lengthSize };
}

/** Length-prefixed NAL units → Annex B, with `prefix` units first; null when a length is bad. */
export function avccToAnnexB(
  d: Uint8Array,
  lengthSize: number,
  prefix: readonly Uint8Array[] = [],
): Uint8Array | null {
  const units: Uint8Array[] = [...prefix];
  for (let at = 0; at < d.length;) {
    if (at + lengthSize > d.length) return null;
    let n = 0;
    for (let k = 0; k < lengthSize; k++) n = n * 256 + d[at + k]!;
    at += lengthSize;
    if (n === 0 || at + n > d.length) return null;
    units.push(d.subarray(at, at + n));
    at += n;
  }
  const out = new Uint8Array(units.reduce((sum, u) => sum + 4 + u.length, 0));
  let w = 0;
  for (const u of units) {
    out.set(START_CODE, w);
    out.set(u, w + 4);
    w += 4 + u.length;
  }
  return out;
}

const AVC_CODEC_ID = 7;
const FRAME_KEY = 1;
const AVC_SEQUENCE_HEADER = 0;
const AVC_NALU = 1;

export function createFlvH264Reader(options: FlvH264ReaderOptions): FlvH264Reader {
  let config: AvcConfig | null = null;
  const report = (kind: FlvH264ErrorKind, message: string) => options.onError?.({ kind, message });
  const flv = createFlvParser({
    ...(options.maxTagBytes ? { maxTagBytes: options.maxTagBytes } : {}),
    onError: (e) => report(e.kind, e.message),
    onTag(tag) {
      if (tag.type !== FLV_TAG_VIDEO) return; // script data (onMetaData), audio: not ours
      const d = tag.data;
      if (d.length < 5 || (d[0]! & 0x0f) !== AVC_CODEC_ID) {
        report('not-h264', `FLV video tag with codec id ${(d[0] ?? 0) & 0x0f}, not AVC (7)`);
        return;
      }
      const payload = d.subarray(5);
      if (d[1] === AVC_SEQUENCE_HEADER) {
        config = parseAvcConfig(payload);
        if (!config) report('bad-config', 'AVC decoder configuration record that does not parse');
        return;
      }
      if (d[1] !== AVC_NALU) return; // 2: end of sequence
      if (!config) {
        report('no-config', 'H.264 frame before its decoder configuration');
        return;
      }
      const key = d[0]! >> 4 === FRAME_KEY;
      const data = avccToAnnexB(
        payload,
        config.lengthSize,
        key ? [...config.sps, ...config.pps] : [],
      );
      if (!data) {
        report('bad-nal-length', 'NAL unit length past the end of the frame');
        return;
      }
      options.onAccessUnit({ data, key, timestampMs: tag.timestampMs });
    },
  });
  return {
    feed: (chunk) => flv.feed(chunk),
    flush: () => flv.flush(),
    reset() {
      flv.reset();
      config = null;
    },
    get config() {
      return config;
    },
  };
}
