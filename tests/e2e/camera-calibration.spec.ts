/// <reference lib="dom" />
/**
 * Looking through a camera and calibrating it, end to end (issue 15; real Mosquitto, a real
 * `serveCamera` with ffmpeg's test source, the simulated arm, Debian Chromium):
 *  - view-through fills the 3D view with the live picture, opaque, and draws the twin
 *    translucent over it (the picture shows through the arm); leaving puts the 3D view back;
 *  - a calibration set by eye changes the view, is saved retained, and is still in force after
 *    the page reloads;
 *  - four (here five) clicked points, each a twin point matched to where a camera at a known
 *    pose sees it, give back that pose.
 * The camera is stopped before pixels are compared, so the picture holds still.
 */
import type { Page } from '@playwright/test';
import mqtt, { type MqttClient } from 'mqtt';
import { serveCamera, type ServedCameras } from '@armtwin/camera';
import { projectPoint, type CameraPose, type Vec3 } from '@armtwin/camera/client';
import { encodeMove } from '@armtwin/protocol';
import { expect, renderedAngles, shot, test, type HudWindow } from './fixtures.ts';
import {
  diffSnaps,
  picturePatch,
  showTwin,
  snapPatch,
  snapView,
  viewAspect,
  SNAP_H,
} from './support/view-pixels.ts';

test.describe.configure({ mode: 'serial' });

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

const ANNOUNCED: CameraPose = { position: [600, -400, 450], lookAt: [0, 0, 220] };

interface ViewCamera {
  fov: number;
  position: { x: number; y: number; z: number };
}
const viewCamera = (page: Page) =>
  page.evaluate(() => {
    const c = (
      window as unknown as {
        __armtwin: { viewer: { camera: ViewCamera } };
      }
    ).__armtwin.viewer.camera;
    return { fov: c.fov, position: { x: c.position.x, y: c.position.y, z: c.position.z } };
  });

/** Each material of the live twin: its opacity, and whether it is drawn as transparent. */
const twinLooks = (page: Page) =>
  page.evaluate(() => {
    const out: string[] = [];
    const robot = (
      window as unknown as {
        __armtwin: {
          viewer: {
            liveRobot: {
              traverse(
                fn: (o: { material?: { opacity: number; transparent: boolean } }) => void,
              ): void;
            };
          };
        };
      }
    ).__armtwin.viewer.liveRobot;
    robot.traverse((o) => {
      if (o.material) out.push(`${o.material.opacity}/${o.material.transparent}`);
    });
    return out;
  });

const cameraRegion = (page: Page, label: string) =>
  page.getByRole('region', { name: `Camera ${label}`, exact: true });

/** The first retained message on `topic`, parsed (null: an empty one). */
async function retained(url: string, topic: string): Promise<Record<string, unknown> | null> {
  const c = await mqtt.connectAsync(url, { reconnectPeriod: 0 });
  try {
    const got = new Promise<string>((resolve) =>
      c.on('message', (t, p) => t === topic && resolve(p.toString())),
    );
    await c.subscribeAsync(topic, { qos: 1 });
    const text = await Promise.race([got, sleep(3000).then(() => '')]);
    return text ? (JSON.parse(text) as Record<string, unknown>) : null;
  } finally {
    await c.endAsync(true);
  }
}

test.describe('camera view-through and calibration', () => {
  // The twin's materials and the view's pixels are read back: only a main-thread view has them.
  test.use({ hudQuery: '&render=main' });
  let cam: ServedCameras | null = null;
  let client: MqttClient | null = null;
  const cleanup: string[] = [];

  test.afterEach(async () => {
    await cam?.stop();
    cam = null;
    for (const t of cleanup.splice(0)) await client?.publishAsync(t, '', { qos: 1, retain: true });
    await client?.endAsync(true);
    client = null;
  });

  async function announce(page: Page, armId: string, brokerUrl: string) {
    cam = await serveCamera({
      cameras: [{ armId, camId: 'front', label: 'Front', source: 'testsrc' }],
      port: 0,
      mqttUrl: '',
    });
    client = await mqtt.connectAsync(brokerUrl, { reconnectPeriod: 0 });
    const topic = `arm/${armId}/camera/front`;
    cleanup.push(`${topic}/calibration`, topic);
    await client.publishAsync(
      topic,
      JSON.stringify({
        url: `${cam.url}/camera/front.mjpeg`,
        kind: 'mjpeg',
        label: 'Front',
        pose: ANNOUNCED,
        fovDeg: 50,
      }),
      { qos: 1, retain: true },
    );
    const view = cameraRegion(page, 'Front');
    await expect(view.getByTestId('camera-age')).toHaveText(/last frame \d+\.\d s ago/, {
      timeout: 20_000,
    });
    return { view, topic };
  }

  test('the live picture fills the view, the twin translucent over it; a calibration by eye is kept across a reload', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    test.setTimeout(120_000);
    const { page } = hud;
    const { view, topic } = await announce(page, arm.id, stack.broker.url);
    const orbit = await viewCamera(page);
    const looks = await twinLooks(page);
    await snapView(page, 'orbit');

    await view.getByRole('button', { name: 'View through this camera' }).click();
    expect((await viewCamera(page)).fov).toBe(50);
    // The picture holds still from here: the last frame stays in the view.
    await cam!.stop();
    cam = null;
    await expect(view.getByTestId('camera-age')).toHaveText(/camera offline since/, {
      timeout: 15_000,
    });
    await sleep(500); // the last frame's texture upload (at most TEXTURE_HZ a second)
    await shot(page, testInfo, 'camera-view-through');
    await snapView(page, 'through');
    await showTwin(page, false);
    await snapView(page, 'picture-alone');
    await showTwin(page, true);

    // Away from the arm, the view shows the camera's own picture, where the camera sees it.
    const aspect = await viewAspect(page);
    let matching = 0;
    for (const [px, py] of [
      [0.15, 0.2],
      [0.85, 0.2],
      [0.15, 0.85],
      [0.85, 0.85],
    ] as const) {
      const inView = await snapPatch(
        page,
        'picture-alone',
        0.5 + ((px - 0.5) * 4) / 3 / aspect,
        py,
      );
      const inPicture = await picturePatch(view, px, py, 8 / SNAP_H);
      if (inView.every((v, i) => Math.abs(v - inPicture[i]!) < 20)) matching++;
    }
    expect(matching).toBeGreaterThanOrEqual(3);
    // The twin is drawn over the picture (many pixels differ where it is) and the picture
    // shows through it (there, the view still follows the picture).
    const twin = await diffSnaps(page, 'through', 'picture-alone');
    expect(twin.changed).toBeGreaterThan(400);
    expect(twin.correlation).toBeGreaterThan(0.3);

    // By eye: a narrower field of view, the camera higher: the view follows the draft.
    await view.getByText('Calibrate', { exact: true }).click();
    await view.getByLabel('Field of view (degrees)').fill('40');
    await view.getByLabel('Position z (mm)').fill('520');
    await expect.poll(async () => (await viewCamera(page)).fov).toBe(40);
    await snapView(page, 'calibrated');
    expect((await diffSnaps(page, 'through', 'calibrated')).changed).toBeGreaterThan(1000);
    await shot(page, testInfo, 'camera-calibrated-by-eye');
    await view.getByRole('button', { name: 'Save calibration' }).click();
    await expect(view.getByText(/Calibrated by anonymous at \d\d:\d\d:\d\d/)).toBeVisible();
    const saved = await retained(stack.broker.url, `${topic}/calibration`);
    expect(saved).toMatchObject({
      pose: { position: [600, -400, 520], lookAt: [0, 0, 220] },
      fovDeg: 40,
      by: 'anonymous',
    });

    // Back to the 3D view: the orbit view and the opaque twin as they were.
    await view.getByRole('button', { name: 'Back to the 3D view' }).click();
    const back = await viewCamera(page);
    expect(back.fov).toBe(orbit.fov);
    for (const k of ['x', 'y', 'z'] as const)
      expect(back.position[k]).toBeCloseTo(orbit.position[k], 6);
    // The runtime takes the view's change with its next message (as the render worker does).
    await expect.poll(() => twinLooks(page)).toEqual(looks);
    // The floor and grid are back (they cover much of the view; the camera's screen and the
    // resolution of the moment make a few pixels differ).
    await snapView(page, 'orbit-again');
    expect((await diffSnaps(page, 'orbit', 'orbit-again')).changed).toBeLessThan(
      0.05 * 480 * SNAP_H,
    );

    // Retained: a reloaded page looks through the calibrated pose.
    await page.reload();
    await page.waitForFunction(
      () => (window as unknown as { __armtwin?: { ready: boolean } }).__armtwin?.ready === true,
    );
    const again = cameraRegion(page, 'Front');
    await again.getByRole('button', { name: 'View through this camera' }).click();
    await expect.poll(async () => (await viewCamera(page)).fov).toBe(40);
    await again.getByText('Calibrate', { exact: true }).click();
    await expect(again.getByLabel('Position z (mm)')).toHaveValue('520');
    await expect(again.getByText(/Calibrated by anonymous/)).toBeVisible();

    // Back to the announced pose: the calibration is cleared for everyone.
    await again.getByRole('button', { name: 'Back to the announced pose' }).click();
    await expect.poll(async () => (await viewCamera(page)).fov).toBe(50);
    expect(await retained(stack.broker.url, `${topic}/calibration`)).toBeNull();
  });

  test('four clicked points give back the pose of the camera that sees them', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    test.setTimeout(120_000);
    const { page } = hud;
    const { view, topic } = await announce(page, arm.id, stack.broker.url);
    // The camera really is here (the announcement is a rough guess).
    const truth: CameraPose = { position: [720, -260, 540], lookAt: [30, 10, 190] };
    const truthFov = 42;

    const control = `arm/${arm.id}/control`;
    const jog = async (pwm: number[]) => {
      const group = `{${pwm.map((p, id) => encodeMove(id, p, 400)).join('')}}`;
      await client!.publishAsync(control, group, { qos: 1 });
      // Until the arm is there, the page has its report of it, and the twin is drawn there
      // and holds still (still alone is not enough: on a loaded page the twin can stand at
      // the end of its prediction while the last reports are still on their way).
      const seen = () =>
        page.evaluate(() => {
          const s = (window as unknown as HudWindow).__armtwin!.store;
          return { pwm: Array.from(s.pwm), angle: Array.from(s.angle) };
        });
      await expect
        .poll(async () => {
          const a = await renderedAngles(page);
          await sleep(200);
          const b = await renderedAngles(page);
          const page_ = await seen();
          return (
            arm.observer.pwm.slice(0, 4).every((v, i) => Math.abs(v - pwm[i]!) <= 2) &&
            page_.pwm.slice(0, 4).every((v, i) => Math.abs(v - pwm[i]!) <= 2) &&
            b.every((v, i) => !(Math.abs(v - page_.angle[i]!) >= 0.05)) &&
            a.every((v, i) => Math.abs(v - b[i]!) < 0.05)
          );
        })
        .toBe(true);
    };
    const twinPoint = (name: string) =>
      page.evaluate((name) => {
        const v = (
          window as unknown as {
            __armtwin: {
              viewer: {
                world: { worldToLocal(p: unknown): unknown };
                liveRobot: {
                  links: Record<
                    string,
                    {
                      position: { clone(): { x: number; y: number; z: number } };
                      getWorldPosition(p: unknown): unknown;
                    }
                  >;
                };
              };
            };
          }
        ).__armtwin.viewer;
        const link = v.liveRobot.links[name]!;
        const p = link.position.clone();
        link.getWorldPosition(p);
        v.world.worldToLocal(p);
        return [p.x * 1000, p.y * 1000, p.z * 1000] as Vec3;
      }, name);

    await view.getByText('Calibrate', { exact: true }).click();
    const canvas = view.locator('canvas');
    const clicked: { world: Vec3; image: [number, number] }[] = [];
    const pick = async (name: string) => {
      await view.getByLabel('Twin point').selectOption(name);
      const world = await twinPoint(name);
      const image = projectPoint(truth, truthFov, 640 / 480, world)!;
      expect(image.every((v) => v > 0.02 && v < 0.98)).toBe(true);
      const box = (await canvas.boundingBox())!;
      await canvas.click({ position: { x: image[0] * box.width, y: image[1] * box.height } });
      clicked.push({ world, image });
    };
    // The arm bent, turned: four of its joints; then turned the other way: the tip again.
    await jog([1800, 1250, 1900, 1300]);
    for (const name of ['base_link', 'forearm', 'wrist', 'tip']) await pick(name);
    await jog([1200, 1300, 1800, 1500]);
    await pick('tip');
    await expect(view.getByTestId('calib-point-count')).toContainText('5 points');
    await view.getByRole('button', { name: 'Solve from the points' }).click();
    await expect(view.getByRole('status')).toContainText('Solved');
    await view.getByRole('button', { name: 'Save calibration' }).click();
    await expect(view.getByText(/Calibrated by anonymous/)).toBeVisible();
    const saved = (await retained(stack.broker.url, `${topic}/calibration`)) as {
      pose: CameraPose;
      fovDeg: number;
    };

    // Clicks land on whole CSS pixels of a 320-pixel-wide picture: within a few cm and degrees.
    // The distance along the view axis is the least determined (it trades against the field
    // of view): the same clicks gave 56 mm when the panel sat at another sub-pixel offset (the
    // a11y spec run first), with the field of view 3.07° off, so the bounds are 70 mm and 4°;
    // the direction and each point's reprojection below are the tight checks.
    const dist = Math.hypot(...saved.pose.position.map((v, i) => v - truth.position[i]!));
    expect(dist).toBeLessThan(70);
    expect(Math.abs(saved.fovDeg - truthFov)).toBeLessThan(4);
    const dir = (p: CameraPose) => {
      const d = p.lookAt.map((v, i) => v - p.position[i]!);
      const n = Math.hypot(...d);
      return d.map((v) => v / n);
    };
    const cos = dir(saved.pose).reduce((s, v, i) => s + v * dir(truth)[i]!, 0);
    expect((Math.acos(Math.min(1, cos)) * 180) / Math.PI).toBeLessThan(3);
    // Each point lands within two picture pixels (of 480) of where it was clicked.
    for (const c of clicked) {
      const at = projectPoint(saved.pose, saved.fovDeg, 640 / 480, c.world)!;
      expect(Math.hypot((at[0] - c.image[0]) * 640, (at[1] - c.image[1]) * 480)).toBeLessThan(5);
    }
    await view.getByRole('button', { name: 'View through this camera' }).click();
    await sleep(1000);
    await shot(page, testInfo, 'camera-four-point-view-through');
  });
});
