/**
 * What ffmpeg is told to do, pure: a camera source (the test source, a V4L2 device, an RTSP
 * URL, an MJPEG-over-HTTP URL) → one ffmpeg command line that writes JPEGs in SMJPEG on one
 * pipe and H.264 in FLV on another, from one decode of the source.
 *
 * Encoder settings (`DEFAULT_ENCODER_OPTIONS`), chosen for latency first:
 * - MJPEG: `-q:v 5` (about 20 KB a frame at 640×480), every frame stands alone; one thread,
 *   because ffmpeg's MJPEG encoder otherwise runs frame threads, which hold each frame back by
 *   one frame (measured: 35 ms → 3 ms from the source's clock to the server).
 * - H.264: libx264 `-preset veryfast -tune zerolatency` (no look-ahead, no frame threads, no
 *   B-frames), constrained baseline (what every WebCodecs decoder takes), a key frame every
 *   second (`-g` = fps, scene cuts off) so a new or lagging viewer starts within a second, CRF 23
 *   capped at 1.5 Mbit/s with a 0.5 s VBV buffer so key frames do not burst, one thread.
 * - `-fps_mode passthrough`: frames are never duplicated or held back to make a constant rate;
 *   `-enc_time_base 1:1000`: time stamps in ms, so two frames a little closer than 1/fps apart
 *   (clock jitter) do not round to one time stamp, which the encoder refuses ("Invalid pts").
 * - `-flush_packets 1`: each frame leaves ffmpeg's pipe buffer as soon as it is encoded.
 *
 * Frame times are capture times on the wall clock (epoch ms), carried to the server in the
 * containers on the pipes (FLV for H.264, SMJPEG for the JPEGs: each frame with its time stamp;
 * ./capture-time.ts puts back the high bits they drop). Per source: the test source's
 * `setpts=RTCTIME` (./time-stripe.ts, the instant the frame is drawn); a V4L2 device's kernel
 * buffer time (when the driver had the frame), made wall clock by `-ts mono2abs` (the kernel's
 * is `CLOCK_MONOTONIC`; mono2abs rather than `abs`, which stops ffmpeg on a device whose times
 * it cannot place, v4l2loopback's for one); an RTSP camera's `-use_wallclock_as_timestamps 1`
 * (when ffmpeg read the frame: RTP's own times start at a random offset); an MJPEG URL's
 * `setpts=RTCTIME` (when ffmpeg decoded it: that demuxer has no times, and its 1/25 s time
 * base would round a read time to 40 ms). `-copyts` keeps them: by default ffmpeg shifts every
 * stream to start at 0.
 */
import { timeStripeFilter, WALL_CLOCK_PTS } from './time-stripe.ts';

export type CameraSource =
  | { type: 'testsrc' }
  | { type: 'v4l2'; device: string }
  | { type: 'rtsp'; url: string }
  | { type: 'mjpeg-url'; url: string };
export type SourceType = CameraSource['type'];

/** `testsrc`, `/dev/video0`, `rtsp://…` / `rtsps://…`, or `http(s)://…` (an MJPEG stream). */
export function parseSource(text: string): CameraSource {
  if (text === 'testsrc') return { type: 'testsrc' };
  if (/^\/dev\/[A-Za-z0-9/_.-]+$/.test(text) && !text.includes('..'))
    return { type: 'v4l2', device: text };
  let url: URL | null = null;
  try {
    url = new URL(text);
  } catch {
    // not a URL: falls through to the error
  }
  if (url?.protocol === 'rtsp:' || url?.protocol === 'rtsps:') return { type: 'rtsp', url: text };
  if (url?.protocol === 'http:' || url?.protocol === 'https:')
    return { type: 'mjpeg-url', url: text };
  throw new RangeError(
    `camera source ${JSON.stringify(text).slice(0, 80)}: expected testsrc, a V4L2 device (/dev/video0), an rtsp:// URL or an http(s):// MJPEG URL`,
  );
}

/** A source for logs and metrics: a URL loses its user name and password. */
export function describeSource(s: CameraSource): string {
  switch (s.type) {
    case 'testsrc':
      return 'testsrc';
    case 'v4l2':
      return s.device;
    case 'rtsp':
    case 'mjpeg-url': {
      const u = new URL(s.url);
      u.username = '';
      u.password = '';
      return u.toString();
    }
    default:
      return assertNever(s);
  }
}

export interface EncoderOptions {
  /** Frame size out, px (a camera's picture is scaled and letterboxed to it). */
  width: number;
  height: number;
  /** Frame rate asked of the test source and of a V4L2 device. */
  fps: number;
  /** MJPEG quality, 2 (best) – 31. */
  mjpegQuality: number;
  /** libx264 preset. */
  h264Preset: string;
  /** Frames between key frames; 0 = one second's worth (`fps`). */
  gop: number;
  h264Crf: number;
  /** Bit-rate cap, kbit/s, and the VBV buffer, kbit. */
  h264MaxrateKbps: number;
  h264BufsizeKbps: number;
  /** Encoder threads (1: the least CPU, no added delay at 640×480). */
  h264Threads: number;
  /** V4L2 pixel format asked of the device ('' = its default), e.g. `mjpeg`, `yuyv422`. */
  v4l2InputFormat: string;
  /** RTSP over TCP (true) or UDP. */
  rtspTcp: boolean;
  /** Socket time-out for network sources, ms. */
  networkTimeoutMs: number;
  /**
   * Burn the wall-clock stripe (./time-stripe.ts) into the picture: `auto` = for the test
   * source only.
   */
  timeStripe: boolean | 'auto';
}

export const DEFAULT_ENCODER_OPTIONS: EncoderOptions = {
  width: 640,
  height: 480,
  fps: 30,
  mjpegQuality: 5,
  h264Preset: 'veryfast',
  gop: 0,
  h264Crf: 23,
  h264MaxrateKbps: 1500,
  h264BufsizeKbps: 750,
  h264Threads: 1,
  v4l2InputFormat: '',
  rtspTcp: true,
  networkTimeoutMs: 5000,
  timeStripe: 'auto',
};

/** Which pipe each output goes to: file descriptors of the child (1 = stdout, 3, …). */
export interface FfmpegOutputs {
  mjpeg?: number;
  h264?: number;
}

function inputArgs(s: CameraSource, o: EncoderOptions): string[] {
  switch (s.type) {
    case 'testsrc':
      // -re: lavfi makes frames as fast as it can; this paces them to the wall clock.
      return ['-re', '-f', 'lavfi', '-i', `testsrc2=size=${o.width}x${o.height}:rate=${o.fps}`];
    case 'v4l2':
      return [
        ...['-f', 'v4l2', '-ts', 'mono2abs'],
        '-framerate',
        String(o.fps),
        '-video_size',
        `${o.width}x${o.height}`,
        ...(o.v4l2InputFormat ? ['-input_format', o.v4l2InputFormat] : []),
        '-i',
        s.device,
      ];
    case 'rtsp':
      return [
        ...['-use_wallclock_as_timestamps', '1'],
        '-fflags',
        'nobuffer',
        '-flags',
        'low_delay',
        '-rtsp_transport',
        o.rtspTcp ? 'tcp' : 'udp',
        '-timeout',
        String(o.networkTimeoutMs * 1000),
        '-i',
        s.url,
      ];
    case 'mjpeg-url':
      return [
        '-fflags',
        'nobuffer',
        '-rw_timeout',
        String(o.networkTimeoutMs * 1000),
        '-f',
        'mpjpeg',
        '-i',
        s.url,
      ];
    default:
      return assertNever(s);
  }
}

/** The filter chain from the decoded source to the encoders' common input. */
export function filterChain(s: CameraSource, o: EncoderOptions): string {
  const { width: w, height: h } = o;
  const steps: string[] = [];
  const stripe = o.timeStripe === true || (o.timeStripe === 'auto' && s.type === 'testsrc');
  // the wall clock as each picture is made or decoded, in ms (the stripe sets it itself): the
  // test source's own times start at 0, an MJPEG URL has none (see the top of this file)
  if (!stripe && (s.type === 'testsrc' || s.type === 'mjpeg-url')) steps.push(...WALL_CLOCK_PTS);
  if (s.type !== 'testsrc')
    steps.push(
      `scale=${w}:${h}:force_original_aspect_ratio=decrease`,
      `pad=${w}:${h}:(ow-iw)/2:(oh-ih)/2`,
    );
  steps.push('format=yuv420p');
  if (stripe) steps.push(timeStripeFilter(w, h));
  return steps.join(',');
}

/** The whole command line (without the program name). */
export function ffmpegArgs(
  s: CameraSource,
  options: Partial<EncoderOptions>,
  out: FfmpegOutputs,
): string[] {
  const o = { ...DEFAULT_ENCODER_OPTIONS, ...options };
  if (out.mjpeg === undefined && out.h264 === undefined)
    throw new RangeError('ffmpeg needs at least one output');
  const both = out.mjpeg !== undefined && out.h264 !== undefined;
  const gop = o.gop > 0 ? o.gop : Math.round(o.fps);
  const graph = `[0:v]${filterChain(s, o)}${both ? ',split=2[m][h]' : out.mjpeg !== undefined ? '[m]' : '[h]'}`;
  const args = ['-hide_banner', '-nostdin', '-nostats', '-loglevel', 'error', ...inputArgs(s, o)];
  args.push('-copyts', '-filter_complex', graph);
  if (out.mjpeg !== undefined)
    args.push(
      ...['-map', '[m]', '-an', '-fps_mode', 'passthrough', '-enc_time_base', '1:1000'],
      ...['-c:v', 'mjpeg', '-q:v', String(o.mjpegQuality), '-threads', '1'],
      ...['-flush_packets', '1', '-f', 'smjpeg', `pipe:${out.mjpeg}`],
    );
  if (out.h264 !== undefined)
    args.push(
      ...['-map', '[h]', '-an', '-fps_mode', 'passthrough', '-enc_time_base', '1:1000'],
      ...['-c:v', 'libx264', '-preset', o.h264Preset, '-tune', 'zerolatency'],
      ...['-profile:v', 'baseline', '-pix_fmt', 'yuv420p', '-bf', '0'],
      ...['-g', String(gop), '-keyint_min', String(gop), '-sc_threshold', '0'],
      ...['-crf', String(o.h264Crf), '-maxrate', `${o.h264MaxrateKbps}k`],
      ...['-bufsize', `${o.h264BufsizeKbps}k`, '-threads', String(o.h264Threads)],
      ...['-flush_packets', '1', '-flvflags', 'no_duration_filesize', '-f', 'flv'],
      `pipe:${out.h264}`,
    );
  return args;
}

function assertNever(x: never): never {
  throw new Error(`unhandled camera source ${JSON.stringify(x)}`);
}
