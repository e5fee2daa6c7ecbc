/**
 * H.264 access units (Annex B, as the `h264-ws` wire carries them) → an FLV byte stream, pure:
 * the inverse of ./flv-h264.ts. The recorder pipes it into `ffmpeg -f flv -c copy`, which then
 * cuts MP4 segments without decoding a pixel; FLV is the simplest container that carries each
 * frame's own time stamp (ms), so the segments keep the camera server's frame times.
 *
 * Layout (Adobe FLV v10.1, E.4): the 9-byte header (video only) and `PreviousTagSize0`; one
 * sequence-header tag (the AVCDecoderConfigurationRecord of the first key frame's SPS and PPS);
 * then one video tag per access unit, its NAL units length-prefixed (4 bytes), SPS, PPS and
 * access unit delimiters left out (they live in the configuration record).
 */
import { NAL, nalUnits } from './nal.ts';
import { FLV_TAG_VIDEO } from './flv-parser.ts';

const AVC_CODEC_ID = 7;
const FRAME_KEY = 1;
const FRAME_INTER = 2;

/** The FLV file header (video only) and `PreviousTagSize0`. */
export function flvHeader(): Uint8Array {
  return new Uint8Array([0x46, 0x4c, 0x56, 1, 0x01, 0, 0, 0, 9, 0, 0, 0, 0]);
}

/** One FLV tag with its trailing `PreviousTagSize`. */
export function flvTag(type: number, timestampMs: number, data: Uint8Array): Uint8Array {
  if (!Number.isInteger(timestampMs) || timestampMs < 0 || timestampMs > 0xffffffff)
    throw new RangeError(`FLV time stamp ${timestampMs} is not a whole number of ms in 32 bits`);
  const out = new Uint8Array(11 + data.length + 4);
  const view = new DataView(out.buffer);
  view.setUint32(0, data.length); // the low 3 bytes are the size…
  out[0] = type; // …under the type byte
  view.setUint32(4, ((timestampMs & 0xffffff) << 8) | (timestampMs >>> 24)); // u24 + upper u8
  out.set(data, 11); // stream id: bytes 8-10 stay 0
  view.setUint32(11 + data.length, 11 + data.length);
  return out;
}

/** The AVCDecoderConfigurationRecord (ISO/IEC 14496-15 5.2.4.1) of one SPS and its PPSs. */
export function avcConfigRecord(sps: Uint8Array, pps: readonly Uint8Array[]): Uint8Array {
  if (sps.length < 4) throw new RangeError('an SPS is at least 4 bytes');
  const size = 6 + 2 + sps.length + 1 + pps.reduce((n, p) => n + 2 + p.length, 0);
  const out = new Uint8Array(size);
  out.set([1, sps[1]!, sps[2]!, sps[3]!, 0xfc | 3, 0xe0 | 1, sps.length >> 8, sps.length & 0xff]);
  out.set(sps, 8);
  let at = 8 + sps.length;
  out[at++] = pps.length;
  for (const p of pps) {
    out[at++] = p.length >> 8;
    out[at++] = p.length & 0xff;
    out.set(p, at);
    at += p.length;
  }
  return out;
}

/** The parameter sets of a key frame, as one string (a change of them needs a new stream). */
export function parameterSets(au: Uint8Array): { sps: Uint8Array; pps: Uint8Array[] } | null {
  const units = nalUnits(au);
  const sps = units.find((u) => u.type === NAL.sps)?.data;
  const pps = units.filter((u) => u.type === NAL.pps).map((u) => u.data);
  return sps && pps.length > 0 ? { sps, pps } : null;
}

/** The same bytes? (Parameter sets are compared to tell an encoder that started over.) */
export function sameBytes(a: Uint8Array, b: Uint8Array): boolean {
  return a.length === b.length && a.every((v, i) => v === b[i]);
}

function videoTag(timestampMs: number, key: boolean, packetType: 0 | 1, body: Uint8Array) {
  const data = new Uint8Array(5 + body.length);
  data[0] = ((key ? FRAME_KEY : FRAME_INTER) << 4) | AVC_CODEC_ID;
  data[1] = packetType; // bytes 2-4: composition time 0 (no B-frames)
  data.set(body, 5);
  return flvTag(FLV_TAG_VIDEO, timestampMs, data);
}

/**
 * The start of a stream: the header and the sequence header of `keyFrame`'s parameter sets, or
 * null when the access unit carries none (only a key frame from the server does).
 */
export function flvStart(keyFrame: Uint8Array): Uint8Array | null {
  const ps = parameterSets(keyFrame);
  if (!ps) return null;
  const head = flvHeader();
  const seq = videoTag(0, true, 0, avcConfigRecord(ps.sps, ps.pps));
  const out = new Uint8Array(head.length + seq.length);
  out.set(head, 0);
  out.set(seq, head.length);
  return out;
}

/** One access unit as an FLV video tag at `timestampMs` (from the stream's start). */
export function flvFrame(au: Uint8Array, key: boolean, timestampMs: number): Uint8Array {
  const units = nalUnits(au).filter(
    (u) => u.type !== NAL.sps && u.type !== NAL.pps && u.type !== NAL.aud,
  );
  const body = new Uint8Array(units.reduce((n, u) => n + 4 + u.data.length, 0));
  const view = new DataView(body.buffer);
  let at = 0;
  for (const u of units) {
    view.setUint32(at, u.data.length);
    body.set(u.data, at + 4);
    at += 4 + u.data.length;
  }
  return videoTag(timestampMs, key, 1, body);
}
