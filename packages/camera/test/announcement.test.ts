import { describe, expect, it } from 'vitest';
import {
  cameraStreams,
  cameraTopic,
  encodeAnnouncement,
  parseAnnouncement,
  parseCameraMessage,
  parseCameraTopic,
  type AnnouncementRejection,
} from '../src/announcement.ts';

const GOOD = {
  url: 'http://127.0.0.1:8090/camera/front.mjpeg',
  kind: 'mjpeg',
  label: 'Front',
};
const json = (o: unknown) => JSON.stringify(o);

describe('camera announcement (PROTOCOL.md §7)', () => {
  it('takes {url, kind, label} and the optional pose and fovDeg, ignoring unknown fields', () => {
    const r = parseAnnouncement(
      json({
        ...GOOD,
        pose: { position: [400, -300, 500], lookAt: [150, 0, 100] },
        fovDeg: 55,
        vendor: { anything: true },
      }),
    );
    expect(r).toEqual({
      type: 'camera',
      camera: {
        ...GOOD,
        pose: { position: [400, -300, 500], lookAt: [150, 0, 100] },
        fovDeg: 55,
        alternates: [],
      },
    });
  });

  it('an empty payload removes the camera', () => {
    expect(parseAnnouncement('')).toEqual({ type: 'removed' });
    expect(parseAnnouncement(new Uint8Array(0))).toEqual({ type: 'removed' });
  });

  it('reads bytes as UTF-8', () => {
    const r = parseAnnouncement(
      new TextEncoder().encode(json({ ...GOOD, label: 'Greifer – oben' })),
    );
    expect(r.type === 'camera' && r.camera.label).toBe('Greifer – oben');
  });

  it('takes the h264-ws kind over ws(s), and alternates, main stream first', () => {
    const r = parseAnnouncement(
      json({
        ...GOOD,
        alternates: [{ url: 'wss://cams.example/camera/front.h264', kind: 'h264-ws' }],
      }),
    );
    expect(r.type).toBe('camera');
    if (r.type !== 'camera') return;
    expect(cameraStreams(r.camera).map((s) => s.kind)).toEqual(['mjpeg', 'h264-ws']);
  });

  const rejected: [string, unknown, AnnouncementRejection][] = [
    ['javascript: URL', { ...GOOD, url: 'javascript:alert(document.cookie)' }, 'unsupported-url'],
    [
      'JavaScript: URL with odd case and spaces',
      { ...GOOD, url: ' JavaScript:alert(1)' },
      'unsupported-url',
    ],
    ['data: URL', { ...GOOD, url: 'data:image/jpeg;base64,AAAA' }, 'unsupported-url'],
    ['file: URL', { ...GOOD, url: 'file:///etc/passwd' }, 'unsupported-url'],
    ['relative URL', { ...GOOD, url: '/camera/front.mjpeg' }, 'bad-url'],
    ['URL that is not a string', { ...GOOD, url: 42 }, 'bad-url'],
    ['missing URL', { kind: 'mjpeg', label: 'x' }, 'bad-url'],
    ['overlong URL', { ...GOOD, url: `http://x/${'a'.repeat(3000)}` }, 'bad-url'],
    [
      'URL with credentials',
      { ...GOOD, url: 'http://admin:admin@cam.local/video' },
      'url-credentials',
    ],
    ['unknown kind', { ...GOOD, kind: 'hls' }, 'unsupported-kind'],
    ['missing kind', { url: GOOD.url, label: 'x' }, 'unsupported-kind'],
    ['mjpeg over ws', { ...GOOD, url: 'ws://x/cam' }, 'url-kind-mismatch'],
    ['h264-ws over http', { ...GOOD, kind: 'h264-ws' }, 'url-kind-mismatch'],
    ['empty label', { ...GOOD, label: '  ' }, 'bad-label'],
    ['label that is not a string', { ...GOOD, label: ['Front'] }, 'bad-label'],
    ['label with a control character', { ...GOOD, label: 'Front\u0007' }, 'bad-label'],
    ['label with a bidi override', { ...GOOD, label: 'gpj.\u202Eexe' }, 'bad-label'],
    ['overlong label', { ...GOOD, label: 'x'.repeat(81) }, 'bad-label'],
    ['pose missing lookAt', { ...GOOD, pose: { position: [0, 0, 0] } }, 'bad-pose'],
    [
      'pose with a string',
      { ...GOOD, pose: { position: [0, 0, '1'], lookAt: [1, 1, 1] } },
      'bad-pose',
    ],
    ['pose far away', { ...GOOD, pose: { position: [1e9, 0, 0], lookAt: [0, 0, 0] } }, 'bad-pose'],
    [
      'pose looking at itself',
      { ...GOOD, pose: { position: [1, 2, 3], lookAt: [1, 2, 3] } },
      'bad-pose',
    ],
    ['fov of 0', { ...GOOD, fovDeg: 0 }, 'bad-fov'],
    ['fov as a string', { ...GOOD, fovDeg: '60' }, 'bad-fov'],
    [
      'alternate with a javascript: URL',
      { ...GOOD, alternates: [{ url: 'javascript:x', kind: 'h264-ws' }] },
      'bad-alternates',
    ],
    ['alternates not a list', { ...GOOD, alternates: 'ws://x' }, 'bad-alternates'],
    ['array', [GOOD], 'not-object'],
    ['null', null, 'not-object'],
    ['number', 42, 'not-object'],
  ];
  for (const [name, payload, reason] of rejected) {
    it(`rejects ${name} (${reason})`, () => {
      const r = parseAnnouncement(json(payload));
      expect(r.type === 'rejected' && r.reason).toBe(reason);
    });
  }

  it('rejects what is not JSON, not UTF-8 or too large', () => {
    const reason = (p: string | Uint8Array) => {
      const r = parseAnnouncement(p);
      return r.type === 'rejected' ? r.reason : r.type;
    };
    expect(reason('{url:')).toBe('not-json');
    expect(reason(Uint8Array.of(0x7b, 0xff, 0x7d))).toBe('not-json');
    expect(reason(json({ ...GOOD, padding: 'x'.repeat(5000) }))).toBe('too-large');
    expect(reason(json({ ...GOOD, label: 'é'.repeat(40), padding: 'é'.repeat(2000) }))).toBe(
      'too-large',
    );
  });

  it('keeps a hostile label verbatim: it is text for the HUD to show as text', () => {
    const label = '<img src=x onerror=alert(1)>"\'&';
    const r = parseAnnouncement(json({ ...GOOD, label }));
    expect(r.type === 'camera' && r.camera.label).toBe(label);
  });

  it('encodes what it parses, and refuses to encode what it would reject', () => {
    const camera = { ...GOOD, kind: 'mjpeg' as const, fovDeg: 60, alternates: [] };
    expect(parseAnnouncement(encodeAnnouncement(camera))).toEqual({ type: 'camera', camera });
    expect(() => encodeAnnouncement({ ...camera, url: 'javascript:x' })).toThrow(RangeError);
  });
});

describe('camera topics', () => {
  it('arm/{armId}/camera/{camId}', () => {
    expect(cameraTopic('arm1', 'front')).toBe('arm/arm1/camera/front');
    expect(parseCameraTopic('arm/arm1/camera/front')).toEqual({ armId: 'arm1', camId: 'front' });
    for (const bad of [
      'arm/arm1/camera',
      'arm/arm1/camera/Front',
      'arm/arm1/status',
      'arm/a/camera/b/c',
      `arm/x/camera/${'a'.repeat(33)}`,
    ])
      expect(parseCameraTopic(bad), bad).toBeNull();
    expect(() => cameraTopic('arm1', '../x')).toThrow(RangeError);
  });

  it('parses topic and payload in one call; a bad topic is its own reason', () => {
    expect(parseCameraMessage('arm/arm1/camera/front', '')).toEqual({
      type: 'removed',
      armId: 'arm1',
      camId: 'front',
    });
    const bad = parseCameraMessage('arm/arm1/camera/FRONT', json(GOOD));
    expect(bad.type === 'rejected' && bad.reason).toBe('bad-topic');
  });
});
