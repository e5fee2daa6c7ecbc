import { describe, expect, test } from 'vitest';
import {
  calibrationTopic,
  encodeCalibration,
  parseCalibration,
  parseCalibrationTopic,
  type CameraCalibration,
} from '../src/calibration.ts';

const good: CameraCalibration = {
  pose: { position: [600, -400, 450], lookAt: [0, 0, 220] },
  fovDeg: 48.5,
  by: 'operator',
  at: '2026-11-24T06:00:00.000Z',
};

describe('camera calibration', () => {
  test('round-trips, and an empty payload clears it', () => {
    expect(parseCalibration(encodeCalibration(good))).toEqual({
      type: 'calibration',
      calibration: good,
    });
    expect(parseCalibration('')).toEqual({ type: 'removed' });
    expect(parseCalibration(new Uint8Array())).toEqual({ type: 'removed' });
  });

  test.each([
    ['not JSON', '{pose', 'not-json'],
    ['an array', '[]', 'not-object'],
    ['no pose', JSON.stringify({ ...good, pose: undefined }), 'bad-pose'],
    [
      'one point twice',
      JSON.stringify({ ...good, pose: { position: [1, 2, 3], lookAt: [1, 2, 3] } }),
      'bad-pose',
    ],
    [
      'a pose out of range',
      JSON.stringify({ ...good, pose: { position: [1e9, 0, 0], lookAt: [0, 0, 0] } }),
      'bad-pose',
    ],
    ['fov 180', JSON.stringify({ ...good, fovDeg: 180 }), 'bad-fov'],
    ['fov as text', JSON.stringify({ ...good, fovDeg: '50' }), 'bad-fov'],
    ['by with a control character', JSON.stringify({ ...good, by: 'a\u0007' }), 'bad-calibration'],
    ['at not a time', JSON.stringify({ ...good, at: 'yesterday' }), 'bad-calibration'],
    ['too large', JSON.stringify({ ...good, pad: 'x'.repeat(5000) }), 'too-large'],
  ])('refuses %s', (_name, payload, reason) => {
    const r = parseCalibration(payload);
    expect(r.type).toBe('rejected');
    expect(r.type === 'rejected' && r.reason).toBe(reason);
    expect(r.type === 'rejected' && r.message.length).toBeGreaterThan(0);
  });

  test('encode refuses what parse would', () => {
    expect(() => encodeCalibration({ ...good, fovDeg: 0 })).toThrow(RangeError);
  });

  test('topic: arm/{armId}/camera/{camId}/calibration, nothing else', () => {
    expect(calibrationTopic('arm1', 'front')).toBe('arm/arm1/camera/front/calibration');
    expect(parseCalibrationTopic('arm/arm1/camera/front/calibration')).toEqual({
      armId: 'arm1',
      camId: 'front',
    });
    for (const t of [
      'arm/arm1/camera/front',
      'arm/arm1/camera/front/other',
      'arm/ARM/camera/front/calibration',
      'arm/arm1/camera/front/calibration/x',
    ])
      expect(parseCalibrationTopic(t)).toBeNull();
    expect(() => calibrationTopic('arm1', 'Front')).toThrow(RangeError);
  });
});
