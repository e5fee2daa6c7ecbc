import { describe, expect, test } from 'vitest';
import { CameraHub } from '../src/core/cameras/CameraHub.ts';
import type { LinkTap } from '../src/core/link/ArmLink.ts';
import { pickStream, usableUrl, withQueryAuth } from '../src/core/cameras/streamUrl.ts';
import type { HudSettings } from '../src/core/config/settings.ts';

function fakeLink(armId: string) {
  const taps: LinkTap[] = [];
  return {
    taps,
    link: { settings: { armId } as HudSettings, tap: (t: LinkTap) => void taps.push(t) },
  };
}

const front = JSON.stringify({
  url: 'http://127.0.0.1:8090/camera/front.mjpeg',
  kind: 'mjpeg',
  label: 'Front',
  alternates: [{ url: 'ws://127.0.0.1:8090/camera/front.h264', kind: 'h264-ws' }],
});

describe('CameraHub', () => {
  test('keeps the selected arm’s cameras, removes on an empty payload, counts rejections', () => {
    const hub = new CameraHub();
    const { taps, link } = fakeLink('arm1');
    hub.attach(link);
    expect(taps[0]!.filter).toBe('arm/arm1/camera/+');
    expect(taps[0]!.matches('arm/arm1/camera/front')).toBe(true);
    expect(taps[0]!.matches('arm/arm1/status')).toBe(false);
    taps[0]!.onMessage('arm/arm1/camera/front', new TextEncoder().encode(front));
    expect(hub.list.map((c) => [c.camId, c.label])).toEqual([['front', 'Front']]);
    const v = hub.version;
    hub.take(
      'arm/arm1/camera/bad',
      JSON.stringify({ url: 'javascript:alert(1)', kind: 'mjpeg', label: 'x' }),
    );
    hub.take('arm/arm1/camera/bad2', '[1]');
    expect(hub.rejected['unsupported-url']).toBe(1);
    expect(hub.rejected['not-object']).toBe(1);
    expect(hub.rejectedTotal).toBe(2);
    expect(hub.version).toBe(v);
    hub.take('arm/arm1/camera/front', '');
    expect(hub.list).toEqual([]);
  });

  test('another arm forgets the previous arm’s cameras and ignores its late messages', () => {
    const hub = new CameraHub();
    const a = fakeLink('arm1');
    hub.attach(a.link);
    a.taps[0]!.onMessage('arm/arm1/camera/front', new TextEncoder().encode(front));
    hub.attach(fakeLink('arm2').link);
    expect(hub.list).toEqual([]);
    a.taps[0]!.onMessage('arm/arm1/camera/front', new TextEncoder().encode(front));
    expect(hub.list).toEqual([]);
  });
});

describe('stream URLs', () => {
  test('only http(s) for mjpeg and ws(s) for h264-ws are used at the sink', () => {
    expect(usableUrl({ url: 'javascript:alert(1)', kind: 'mjpeg' })).toBeNull();
    expect(usableUrl({ url: 'ws://h/x', kind: 'mjpeg' })).toBeNull();
    expect(usableUrl({ url: 'http://u:p@h/x', kind: 'mjpeg' })).toBeNull();
    expect(usableUrl({ url: 'https://h/x', kind: 'mjpeg' })?.href).toBe('https://h/x');
    expect(usableUrl({ url: 'wss://h/x', kind: 'h264-ws' })?.href).toBe('wss://h/x');
  });

  test('h264-ws where VideoDecoder exists, else the mjpeg alternate', () => {
    const cam = {
      url: 'http://h/c.mjpeg',
      kind: 'mjpeg' as const,
      label: 'C',
      alternates: [{ url: 'ws://h/c.h264', kind: 'h264-ws' as const }],
    };
    expect(pickStream(cam, true)?.kind).toBe('h264-ws');
    expect(pickStream(cam, false)?.kind).toBe('mjpeg');
    expect(
      pickStream({ ...cam, url: 'ws://h/c.h264', kind: 'h264-ws', alternates: [] }, false),
    ).toBeNull();
  });

  test('the page’s log-in goes in auth= for a WebSocket', () => {
    const u = withQueryAuth(new URL('ws://h/c.h264'), { username: 'ann', password: 'pw' });
    expect(u.searchParams.get('auth')).toBe(btoa('ann:pw'));
    expect(withQueryAuth(new URL('ws://h/c.h264'), { username: '', password: '' }).search).toBe('');
  });
});
