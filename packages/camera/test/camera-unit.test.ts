import { describe, expect, it } from 'vitest';
import {
  CameraUnit,
  DEFAULT_BACKOFF,
  DEFAULT_CAMERA_FEED_OPTIONS,
  DEFAULT_ENCODER_OPTIONS,
  createCameraServer,
  serveCamera,
  type CameraUnitContext,
} from '../src/index.ts';

const ctx: CameraUnitContext = {
  ffmpeg: 'ffmpeg',
  encoder: DEFAULT_ENCODER_OPTIONS,
  feed: DEFAULT_CAMERA_FEED_OPTIONS,
  backoff: DEFAULT_BACKOFF,
  stallMs: 10_000,
  now: () => 0,
  onFirst: () => {},
};
const spec = { armId: 'arm1', camId: 'front', label: 'Front', source: 'testsrc' };

describe('a served camera (nothing started)', () => {
  it('announces the MJPEG stream first, h264-ws as the alternate, under the base URL', () => {
    const unit = new CameraUnit({ ...spec, fovDeg: 60 }, ctx);
    expect(unit.announcement('https://cams.example:8443/')).toEqual({
      url: 'https://cams.example:8443/camera/front.mjpeg',
      kind: 'mjpeg',
      label: 'Front',
      fovDeg: 60,
      alternates: [{ url: 'wss://cams.example:8443/camera/front.h264', kind: 'h264-ws' }],
    });
    expect(
      new CameraUnit({ ...spec, kinds: ['h264-ws'] }, ctx).announcement('http://h:1').kind,
    ).toBe('h264-ws');
  });

  it('passes an MJPEG URL through as it is, unless it carries a password', () => {
    const unit = new CameraUnit({ ...spec, source: 'http://cam.local/video.mjpg' }, ctx);
    expect(unit.runner).toBeNull();
    expect(unit.announcement('http://h:1')).toMatchObject({
      url: 'http://cam.local/video.mjpg',
      kind: 'mjpeg',
    });
    expect(() => new CameraUnit({ ...spec, source: 'http://admin:pw@cam.local/v' }, ctx)).toThrow(
      /password/,
    );
    expect(
      new CameraUnit({ ...spec, source: 'http://admin:pw@cam.local/v', passThrough: false }, ctx)
        .runner,
    ).not.toBeNull();
  });

  it('refuses a bad id, label, pose or source before anything starts', () => {
    expect(() => new CameraUnit({ ...spec, camId: 'Front!' }, ctx)).toThrow(RangeError);
    expect(() => new CameraUnit({ ...spec, label: 'a\u0000b' }, ctx)).toThrow(RangeError);
    expect(() => new CameraUnit({ ...spec, fovDeg: 200 }, ctx)).toThrow(RangeError);
    expect(() => new CameraUnit({ ...spec, source: 'webcam' }, ctx)).toThrow(RangeError);
    expect(() => createCameraServer({ cameras: [spec, spec] })).toThrow(/two cameras/);
  });

  it('an anonymous camera server listens on loopback only', async () => {
    await expect(serveCamera({ cameras: [spec], host: '0.0.0.0', port: 0 })).rejects.toThrow(
      /beyond loopback/,
    );
  });
});
