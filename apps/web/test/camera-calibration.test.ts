import { describe, expect, test } from 'vitest';
import { CameraHub, placementOf } from '../src/core/cameras/CameraHub.ts';
import { CameraDecoders } from '../src/core/cameras/CameraDecoders.ts';
import type { CameraPlayer } from '../src/core/cameras/CameraPlayer.ts';
import type { LinkTap } from '../src/core/link/ArmLink.ts';
import type { CameraPose } from '@armtwin/camera/client';
import type { HudSettings } from '../src/core/config/settings.ts';
import { draftFromPlacement, placementFromDraft } from '../src/ui/panels/Camera/draft.ts';

const enc = (o: object | string) =>
  new TextEncoder().encode(typeof o === 'string' ? o : JSON.stringify(o));

function fakeLink(command: boolean) {
  const taps: LinkTap[] = [];
  const published: [string, string][] = [];
  return {
    taps,
    published,
    link: {
      settings: { armId: 'arm1', username: 'olga', password: 'pw' } as HudSettings,
      tap: (t: LinkTap) => void taps.push(t),
      permissions: { command, stop: command, deadman: false },
      publishRetained: (topic: string, payload: string) => {
        published.push([topic, payload]);
        return true;
      },
    },
  };
}

/** Delivers a message to the tap that matches it, as the link does. */
const deliver = (taps: LinkTap[], topic: string, payload: object | string) => {
  for (const t of taps) if (t.matches(topic)) t.onMessage(topic, enc(payload));
};

const announcement = {
  url: 'http://127.0.0.1:8090/camera/front.mjpeg',
  kind: 'mjpeg',
  label: 'Front',
  pose: { position: [600, -400, 450], lookAt: [0, 0, 220] },
  fovDeg: 50,
};
const calibration = {
  pose: { position: [620, -380, 440], lookAt: [10, 0, 200] } as CameraPose,
  fovDeg: 47.5,
  by: 'olga',
  at: '2026-11-24T06:00:00.000Z',
};

describe('camera calibration in the hub', () => {
  test('a calibration is laid over the announced pose; clearing it gives the announced one back', () => {
    const hub = new CameraHub();
    const { taps, link } = fakeLink(true);
    hub.attach(link);
    expect(taps.map((t) => t.filter)).toEqual([
      'arm/arm1/camera/+',
      'arm/arm1/camera/+/calibration',
    ]);
    deliver(taps, 'arm/arm1/camera/front', announcement);
    expect(placementOf(hub.list[0]!)).toEqual({ pose: announcement.pose, fovDeg: 50 });
    deliver(taps, 'arm/arm1/camera/front/calibration', calibration);
    expect(hub.list).toHaveLength(1);
    expect(placementOf(hub.list[0]!)).toEqual({ pose: calibration.pose, fovDeg: 47.5 });
    deliver(taps, 'arm/arm1/camera/front/calibration', '');
    expect(placementOf(hub.list[0]!)).toEqual({ pose: announcement.pose, fovDeg: 50 });
  });

  test('a bad calibration is ignored and counted; the camera keeps its pose', () => {
    const hub = new CameraHub();
    const { taps, link } = fakeLink(true);
    hub.attach(link);
    deliver(taps, 'arm/arm1/camera/front', announcement);
    deliver(taps, 'arm/arm1/camera/front/calibration', { ...calibration, fovDeg: 0 });
    deliver(taps, 'arm/arm1/camera/front/calibration', { ...calibration, by: 'x\u202e' });
    expect(hub.rejected['bad-fov']).toBe(1);
    expect(hub.rejected['bad-calibration']).toBe(1);
    expect(placementOf(hub.list[0]!)?.fovDeg).toBe(50);
  });

  test('a removed camera shows no calibration; announced again, its calibration is back', () => {
    const hub = new CameraHub();
    const { taps, link } = fakeLink(true);
    hub.attach(link);
    deliver(taps, 'arm/arm1/camera/front/calibration', calibration);
    expect(hub.list).toEqual([]);
    deliver(taps, 'arm/arm1/camera/front', announcement);
    deliver(taps, 'arm/arm1/camera/front', '');
    expect(hub.list).toEqual([]);
    deliver(taps, 'arm/arm1/camera/front', announcement);
    expect(hub.list[0]!.calibration?.fovDeg).toBe(47.5);
  });

  test('an operator saves retained JSON on the calibration topic; a viewer cannot', () => {
    const hub = new CameraHub();
    const op = fakeLink(true);
    hub.attach(op.link);
    const placement = { pose: calibration.pose, fovDeg: 47.5 };
    expect(hub.canCalibrate).toBe(true);
    expect(hub.saveCalibration('front', placement, 'olga')).toBe(true);
    const [topic, payload] = op.published[0]!;
    expect(topic).toBe('arm/arm1/camera/front/calibration');
    expect(JSON.parse(payload)).toMatchObject({ ...placement, by: 'olga' });
    expect(hub.saveCalibration('front', null, 'olga')).toBe(true);
    expect(op.published[1]).toEqual(['arm/arm1/camera/front/calibration', '']);
    expect(() => hub.saveCalibration('front', { ...placement, fovDeg: 200 }, 'olga')).toThrow(
      RangeError,
    );

    const viewer = fakeLink(false);
    hub.attach(viewer.link);
    expect(hub.canCalibrate).toBe(false);
    expect(hub.saveCalibration('front', placement, 'v')).toBe(false);
    expect(viewer.published).toEqual([]);
  });

  test('the form’s draft: round-trips a placement, refuses blanks, one point twice, fov 180', () => {
    const p = { pose: calibration.pose, fovDeg: 47.5 } as const;
    expect(placementFromDraft(draftFromPlacement(p))).toEqual(p);
    const d = draftFromPlacement(p);
    expect(placementFromDraft({ ...d, px: '' })).toBeNull();
    expect(placementFromDraft({ ...d, fov: '180' })).toBeNull();
    expect(placementFromDraft({ ...d, lx: d.px, ly: d.py, lz: d.pz })).toBeNull();
  });
});

describe('CameraDecoders: a camera decodes only while it is shown', () => {
  function setup() {
    const hub = new CameraHub();
    const { taps, link } = fakeLink(false);
    hub.attach(link);
    const players: { id: string; disposed: boolean }[] = [];
    const decoders = new CameraDecoders(
      hub,
      (_canvas, stream) => {
        const p = { id: stream.url, disposed: false };
        players.push(p);
        return {
          stats: { frames: 0 },
          start: () => {},
          dispose: () => (p.disposed = true),
        } as unknown as CameraPlayer;
      },
      () => false,
      () => ({}) as HTMLCanvasElement,
    );
    deliver(taps, 'arm/arm1/camera/front', announcement);
    deliver(taps, 'arm/arm1/camera/side', { ...announcement, label: 'Side' });
    decoders.update();
    return { taps, decoders, players };
  }
  const open = (players: { disposed: boolean }[]) => players.filter((p) => !p.disposed).length;

  test('folding the panel stops every stream; unfolding opens them again', () => {
    const { decoders, players } = setup();
    expect(open(players)).toBe(2);
    decoders.setPanelOpen(false);
    expect(open(players)).toBe(0);
    expect(decoders.playing('front')).toBe(false);
    decoders.setPanelOpen(true);
    expect(open(players)).toBe(2);
    expect(players).toHaveLength(4);
  });

  test('folded, a camera whose screen is in view, or that the view looks through, still plays', () => {
    const { decoders, players } = setup();
    decoders.setPanelOpen(false);
    decoders.setScene(new Set(['front']), '');
    expect(decoders.playing('front')).toBe(true);
    expect(decoders.playing('side')).toBe(false);
    decoders.setScene(new Set(), 'side');
    expect(decoders.playing('front')).toBe(false);
    expect(decoders.playing('side')).toBe(true);
    expect(open(players)).toBe(1);
  });

  test('a removed camera’s stream is closed and its picture forgotten', () => {
    const { taps, decoders, players } = setup();
    deliver(taps, 'arm/arm1/camera/front', '');
    decoders.update();
    expect(open(players)).toBe(1);
    expect(decoders.pictures.has('front')).toBe(false);
  });
});
