/**
 * The `h264-ws` wire format, browser-safe: each binary WebSocket message is one H.264 access
 * unit in Annex B (start codes, SPS and PPS in front of every key frame) behind a fixed header,
 * big-endian (DataView's default):
 *
 * | offset | size | field                                                                  |
 * | ------ | ---- | ---------------------------------------------------------------------- |
 * | 0      | 1    | version, 1                                                             |
 * | 1      | 1    | flags: bit 0 key frame (IDR, with SPS+PPS), bit 1 replay (see below)   |
 * | 2      | 2    | header length in bytes, 16 (a reader skips what it does not know)     |
 * | 4      | 8    | time stamp, epoch ms, float64: the frame's capture time (see below)    |
 * | 12     | 4    | sequence number of the frame from its encoder (gaps = frames dropped) |
 * | 16     | …    | the access unit                                                        |
 *
 * The time stamp is when the frame was produced (ffmpeg's own frame time on the wall clock:
 * ./capture-time.ts, ./ffmpeg-args.ts), not when the server had it; for a source whose times
 * are not the wall clock, the time it came out of ffmpeg (counted by the server).
 *
 * The payload goes to WebCodecs as it is: `new EncodedVideoChunk({type: key ? 'key' : 'delta',
 * timestamp, data})` on a decoder configured with the codec string of the SPS (./nal.ts) and no
 * `description` (Annex B). A viewer that connects gets the current group of pictures first —
 * the last key frame and what followed it, flagged `replay` — so it can show the live picture at
 * once; it decodes them all but need only display the last.
 */

export const H264_WS_VERSION = 1;
export const H264_WS_HEADER_BYTES = 16;
export const FLAG_KEY = 1;
export const FLAG_REPLAY = 2;

export interface H264Message {
  key: boolean;
  replay: boolean;
  /** Epoch ms: the frame's capture time. */
  timestampMs: number;
  seq: number;
  /** The access unit, Annex B. */
  data: Uint8Array;
}

export const H264_WIRE_ERRORS = ['too-short', 'bad-version', 'bad-header-length'] as const;
export type H264WireError = (typeof H264_WIRE_ERRORS)[number];

/** The 16-byte header alone (the server writes it in front of a shared payload). */
export function encodeH264Header(m: Omit<H264Message, 'data'>): Uint8Array {
  const header = new Uint8Array(H264_WS_HEADER_BYTES);
  const view = new DataView(header.buffer);
  view.setUint8(0, H264_WS_VERSION);
  view.setUint8(1, (m.key ? FLAG_KEY : 0) | (m.replay ? FLAG_REPLAY : 0));
  view.setUint16(2, H264_WS_HEADER_BYTES);
  view.setFloat64(4, m.timestampMs);
  view.setUint32(12, m.seq >>> 0);
  return header;
}

export function encodeH264Message(m: H264Message): Uint8Array {
  const out = new Uint8Array(H264_WS_HEADER_BYTES + m.data.length);
  out.set(encodeH264Header(m), 0);
  out.set(m.data, H264_WS_HEADER_BYTES);
  return out;
}

/** One binary message → the frame, or why not. The payload is a view, not a copy. */
export function decodeH264Message(
  message: ArrayBuffer | Uint8Array,
): { ok: true; message: H264Message } | { ok: false; error: H264WireError } {
  const bytes = message instanceof Uint8Array ? message : new Uint8Array(message);
  if (bytes.length < 4) return { ok: false, error: 'too-short' };
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (view.getUint8(0) !== H264_WS_VERSION) return { ok: false, error: 'bad-version' };
  const headerLength = view.getUint16(2);
  if (headerLength < H264_WS_HEADER_BYTES) return { ok: false, error: 'bad-header-length' };
  if (bytes.length < headerLength) return { ok: false, error: 'too-short' };
  const flags = view.getUint8(1);
  return {
    ok: true,
    message: {
      key: (flags & FLAG_KEY) !== 0,
      replay: (flags & FLAG_REPLAY) !== 0,
      timestampMs: view.getFloat64(4),
      seq: view.getUint32(12),
      data: bytes.subarray(headerLength),
    },
  };
}
