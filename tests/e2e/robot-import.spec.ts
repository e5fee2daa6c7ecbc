/// <reference lib="dom" />
/**
 * Third-party robots imported as they come (rtb-data's KUKA LBR iiwa 14 with DAE meshes and ABB
 * IRB 140 with STL meshes, both with `package://` paths) are drawn by the HUD in Chromium with no
 * failed mesh: `armtwin robot import` into a temporary models folder, `armtwin up --models DIR
 * --arms …` simulating both and serving their folders from disk, one page per arm.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { REPO_ROOT } from '../helpers/services.ts';
import { RTB_ROBOTS, rtbDataDir } from '../helpers/rtb-data.ts';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUp, type UpProcess } from './support/up.ts';

type Xyz = { x: number; y: number; z: number };
/** The parts of a three.js object the view check reads (no three.js import in the test). */
interface Object3DLike {
  isMesh?: boolean;
  matrixWorld: { elements: number[] };
  geometry?: { boundingBox: { min: Xyz; max: Xyz } | null; computeBoundingBox(): void };
}

interface ImportWindow {
  __armtwin?: {
    ready?: boolean;
    joints(): number[];
    robots: { active: { spec: { name: string } } };
    viewer: {
      meshFailures: readonly { url: string; message: string }[];
      drawnWorld: { traverse(fn: (o: { isMesh?: boolean }) => void): void };
      liveRobot: {
        updateMatrixWorld(force: boolean): void;
        traverse(fn: (o: Object3DLike) => void): void;
      } | null;
      camera: {
        matrixWorldInverse: { elements: number[] };
        projectionMatrix: { elements: number[] };
      };
    };
  };
}

/**
 * How far out of the 3D view the live arm reaches: the largest |x| or |y|, in normalised device
 * coordinates, over the corners of every mesh's bounding box (≤ 1: the whole arm is in view).
 */
function armExtentInView(page: Page): Promise<number> {
  return page.evaluate(() => {
    const v = (window as unknown as ImportWindow).__armtwin!.viewer;
    const robot = v.liveRobot!;
    robot.updateMatrixWorld(true);
    const mul = (m: number[], p: number[]) =>
      [0, 1, 2, 3].map(
        (r) => m[r]! * p[0]! + m[4 + r]! * p[1]! + m[8 + r]! * p[2]! + m[12 + r]! * p[3]!,
      );
    let worst = 0;
    robot.traverse((o) => {
      if (!o.isMesh || !o.geometry) return;
      if (!o.geometry.boundingBox) o.geometry.computeBoundingBox();
      const b = o.geometry.boundingBox!;
      for (let i = 0; i < 8; i++) {
        const local = [
          i & 1 ? b.max.x : b.min.x,
          i & 2 ? b.max.y : b.min.y,
          i & 4 ? b.max.z : b.min.z,
          1,
        ];
        const world = mul(o.matrixWorld.elements, local);
        const clip = mul(
          v.camera.projectionMatrix.elements,
          mul(v.camera.matrixWorldInverse.elements, world),
        );
        worst = Math.max(worst, Math.abs(clip[0]! / clip[3]!), Math.abs(clip[1]! / clip[3]!));
      }
    });
    return worst;
  });
}

const ROBOTS = [
  { arm: 'arm1', name: 'iiwa14', source: RTB_ROBOTS.iiwa14, servos: 7 },
  { arm: 'arm2', name: 'irb140', source: RTB_ROBOTS.irb140, servos: 6 },
] as const;

let up: UpProcess;
let models = '';

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(180_000);
  ensureHudBuilt();
  models = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-models-'));
  for (const r of ROBOTS)
    execFileSync(
      process.execPath,
      [
        path.join(REPO_ROOT, 'apps/cli/bin/armtwin.mjs'),
        'robot',
        'import',
        path.join(rtbDataDir(), r.source),
        '--name',
        r.name,
        '--models',
        models,
      ],
      { cwd: REPO_ROOT, stdio: 'pipe' },
    );
  up = await startUp(
    path.join(testInfo.project.outputDir, `armtwin-up-import-${process.pid}.log`),
    ['--models', models, '--arms', ROBOTS.map((r) => `${r.arm}:${r.name}`).join(',')],
  );
});
test.afterAll(async () => {
  await up?.stop();
  if (models) fs.rmSync(models, { recursive: true, force: true });
});

async function open(page: Page, arm: string) {
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  // render=main: the live arm's meshes (measured below) are on the page only then.
  await page.goto(`${up.url}?arm=${arm}&render=main`);
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  // An operator: a viewer opens in Shadow mode, where the Cartesian panel's inputs are off too.
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill('operator');
  await form.getByLabel('Password').fill(demoPassword('operator'));
  await form.getByRole('button', { name: 'Log in' }).click();
}

for (const r of ROBOTS)
  test(`${r.name}: imported as it comes, drawn with every mesh`, async ({ page }, testInfo) => {
    await open(page, r.arm);
    const state = () =>
      page.evaluate(() => {
        const a = (window as unknown as ImportWindow).__armtwin!;
        let meshes = 0;
        a.viewer.drawnWorld.traverse((o) => {
          if (o.isMesh) meshes++;
        });
        return {
          name: a.robots.active.spec.name,
          joints: a.joints().length,
          failures: a.viewer.meshFailures.map((f) => f.message),
          meshes,
        };
      });
    await expect.poll(async () => (await state()).name, { timeout: 30_000 }).toBe(r.name);
    await expect.poll(async () => (await state()).joints, { timeout: 30_000 }).toBe(r.servos);
    const s = await state();
    expect(s.failures).toEqual([]);
    // base + one visual per moving link, on the live arm and the ghost at least.
    expect(s.meshes).toBeGreaterThanOrEqual(2 * (r.servos + 1));
    await expect(page.getByTestId('mesh-failures')).toBeHidden();
    // Framed by its size: the whole arm (over 1 m tall) is in the view, top included.
    const extent = await armExtentInView(page);
    expect(extent).toBeGreaterThan(0.3); // and not a speck in the distance
    expect(extent).toBeLessThan(1);
    // The Cartesian panel starts at a point this arm reaches: where its tip is.
    const z = page.getByLabel('Z', { exact: true });
    // (blank while the new robot's planner loads, after the default arm's 150: fresh clone G2
    // read the blank as 0)
    await expect
      .poll(async () => Number((await z.inputValue()) || NaN), { timeout: 30_000 })
      .toBeGreaterThan(300);
    const tipZ = await z.inputValue();
    await z.fill('');
    await z.fill(tipZ);
    await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
    await shot(page, testInfo, r.name);
  });
