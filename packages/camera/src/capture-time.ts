/**
 * A frame's capture time, pure, browser-safe: the epoch ms at which the frame was produced, read
 * from the time stamp ffmpeg muxed with it rather than from when it arrived.
 *
 * ffmpeg is told to keep its frames' times on the wall clock (./ffmpeg-args.ts: the test
 * source's `setpts=RTCTIME`, a V4L2 device's kernel time converted with `-ts mono2abs`, a
 * network source's read time with `-use_wallclock_as_timestamps 1`, all kept by `-copyts`), but
 * the containers on its pipes cut those times short: FLV (H.264) keeps 31 bits of ms (ffmpeg's
 * muxer drops the sign bit of FLV's 32), SMJPEG (MJPEG) 32. `unwrapStamp` puts the missing high
 * bits back from the server's own clock: the epoch ms nearest to now with the same low bits,
 * exact while the frame is less than 12 days old (2^30 ms).
 *
 * A stamp that is not the wall clock (a source whose times start at 0, a camera whose clock is
 * off) lands far from now; `wallClockStamp` refuses any time over `MAX_STAMP_SKEW_MS` from the
 * clock, and the caller stamps the frame on arrival instead and counts it
 * (`frame-times-arrival`). The same rule judges an MJPEG part's `X-Timestamp` where a recorder
 * reads it.
 */

/** A frame time further than this from the reader's clock is not taken as the frame's, ms. */
export const MAX_STAMP_SKEW_MS = 10_000;

/** Bits of a muxed time stamp that every container on ffmpeg's pipes keeps (FLV: 31). */
export const STAMP_BITS = 31;

const mod = (x: number, m: number) => ((x % m) + m) % m;

/** The epoch ms nearest to `nowMs` whose low `bits` bits are `stamp`'s. */
export function unwrapStamp(stamp: number, nowMs: number, bits = STAMP_BITS): number {
  const span = 2 ** bits;
  const behind = mod(nowMs - stamp, span);
  return behind <= span / 2 ? nowMs - behind : nowMs - behind + span;
}

/** `atMs` when it is a time within `MAX_STAMP_SKEW_MS` of `nowMs`, else null. */
export function wallClockStamp(atMs: number, nowMs: number): number | null {
  return Number.isFinite(atMs) && Math.abs(atMs - nowMs) <= MAX_STAMP_SKEW_MS ? atMs : null;
}

/** A muxed stamp (low bits of epoch ms) → the frame's capture time, or null: not the wall clock. */
export function captureTime(stamp: number, nowMs: number): number | null {
  return wallClockStamp(unwrapStamp(stamp, nowMs), nowMs);
}
