import { describe, expect, it } from 'vitest';
import {
  describeSource,
  ffmpegArgs,
  ffmpegVersion,
  filterChain,
  parseSource,
  DEFAULT_ENCODER_OPTIONS,
} from '../src/index.ts';

describe('camera sources', () => {
  it('parses each kind of source', () => {
    expect(parseSource('testsrc')).toEqual({ type: 'testsrc' });
    expect(parseSource('/dev/video0')).toEqual({ type: 'v4l2', device: '/dev/video0' });
    expect(parseSource('rtsp://cam.local:554/stream1')).toEqual({
      type: 'rtsp',
      url: 'rtsp://cam.local:554/stream1',
    });
    expect(parseSource('http://cam.local/video.mjpg')).toEqual({
      type: 'mjpeg-url',
      url: 'http://cam.local/video.mjpg',
    });
    for (const bad of ['video0', '/dev/../etc/passwd', 'file:///dev/video0', '-i /dev/video0', ''])
      expect(() => parseSource(bad), bad).toThrow(RangeError);
  });
  it('never shows a password in a description', () => {
    expect(describeSource(parseSource('rtsp://admin:secret@cam.local/s'))).toBe(
      'rtsp://cam.local/s',
    );
  });
});

describe('ffmpeg command line', () => {
  it('test source: paced to the wall clock, time stripe, JPEG SMJPEG on fd 1 and H.264 FLV on fd 3', () => {
    const args = ffmpegArgs(parseSource('testsrc'), {}, { mjpeg: 1, h264: 3 });
    const line = args.join(' ');
    expect(line).toContain('-re -f lavfi -i testsrc2=size=640x480:rate=30');
    expect(line).toContain('split=2[m][h]');
    // the frames' times are the wall clock when drawn, and ffmpeg keeps them (no shift to 0)
    expect(line).toContain('setpts=RTCTIME/1000');
    expect(line).toContain(' -copyts -filter_complex ');
    expect(line).toMatch(/-map \[m\] .* -c:v mjpeg .* -f smjpeg pipe:1/);
    expect(line).toMatch(
      /-map \[h\] .* -c:v libx264 -preset veryfast -tune zerolatency -profile:v baseline .* -bf 0 -g 30 .* -f flv pipe:3$/,
    );
  });
  it('one output only, no split', () => {
    const args = ffmpegArgs(parseSource('testsrc'), { timeStripe: false }, { h264: 3 });
    expect(args.join(' ')).not.toContain('split');
    expect(args.join(' ')).not.toContain('mjpeg');
    expect(() => ffmpegArgs(parseSource('testsrc'), {}, {})).toThrow(RangeError);
  });
  it('a camera is scaled and letterboxed to the frame size, without a stripe', () => {
    const f = filterChain(parseSource('/dev/video0'), DEFAULT_ENCODER_OPTIONS);
    expect(f).toBe(
      'scale=640:480:force_original_aspect_ratio=decrease,pad=640:480:(ow-iw)/2:(oh-ih)/2,format=yuv420p',
    );
    const v4l2 = ffmpegArgs(
      parseSource('/dev/video0'),
      { v4l2InputFormat: 'mjpeg' },
      { mjpeg: 1 },
    ).join(' ');
    expect(v4l2).toContain(
      '-f v4l2 -ts mono2abs -framerate 30 -video_size 640x480 -input_format mjpeg -i /dev/video0',
    );
    const rtsp = ffmpegArgs(parseSource('rtsp://cam/s'), {}, { mjpeg: 1 }).join(' ');
    expect(rtsp).toContain('-rtsp_transport tcp -timeout 5000000 -i rtsp://cam/s');
  });
  it("every source's frame times are the wall clock, kept through to the pipes", () => {
    const input = (source: string) => {
      const args = ffmpegArgs(parseSource(source), {}, { h264: 3 });
      expect(args).toContain('-copyts');
      return args.slice(0, args.indexOf('-i')).join(' ');
    };
    expect(input('/dev/video0')).toContain('-ts mono2abs'); // the kernel's capture time
    expect(input('rtsp://cam/s')).toContain('-use_wallclock_as_timestamps 1');
    // an MJPEG URL's frames carry no time: stamped as ffmpeg decodes them, in ms; the test
    // source's as it makes them, stripe or not
    const wallClock = /^settb=1\/1000,setpts=RTCTIME\/1000,/;
    expect(filterChain(parseSource('http://cam/v.mjpg'), DEFAULT_ENCODER_OPTIONS)).toMatch(
      wallClock,
    );
    const plain = { ...DEFAULT_ENCODER_OPTIONS, timeStripe: false };
    expect(filterChain(parseSource('testsrc'), plain)).toBe(
      'settb=1/1000,setpts=RTCTIME/1000,format=yuv420p',
    );
    expect(filterChain(parseSource('testsrc'), DEFAULT_ENCODER_OPTIONS)).toContain(
      'format=yuv420p,settb=1/1000,setpts=RTCTIME/1000,drawbox',
    );
  });
});

describe('ffmpeg on this machine', () => {
  it('ffmpegVersion says null for a program that is not there', () => {
    expect(ffmpegVersion('/nonexistent/ffmpeg')).toBeNull();
  });
});
