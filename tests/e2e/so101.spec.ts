/// <reference lib="dom" />
/**
 * The SO-101 page, end to end: `armtwin up` as `npm start` runs it (the anonymous demo) with its
 * second arm, `so101`, a simulated SO-101 on an emulated Feetech bus behind the real bus
 * gateway; the built HUD in Debian Chromium on `?arm=so101`. The page loads the SO-101 (its
 * URDF's links, every mesh, no request failing), the twin follows the bus, a jog of the gripper
 * (a tool joint, outside the IK chain) moves the emulated servo, and a Cartesian move then leaves
 * the gripper where it was. What the arm does is read on MQTT, from the gateway's sync reads of
 * the bus.
 */
import fs from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { createReader } from '@armtwin/protocol';
import { REPO_ROOT } from '../helpers/services.ts';
import { expect, renderedAngles, shot, test } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { ArmObserver, until } from './support/sim.ts';
import { joints } from './support/robots-window.ts';
import { startUp, type UpProcess } from './support/up.ts';

const ARM = 'so101';
const GRIPPER = 6; // servo 006, the profile's tool joint
const URDF = fs.readFileSync(path.join(REPO_ROOT, 'public/models/so101/so101.urdf'), 'utf8');
const URDF_LINKS = [...URDF.matchAll(/<link\s+name="([^"]+)"/g)].map((m) => m[1]!);

let up: UpProcess;
let observer: ArmObserver;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  // No users file: the anonymous local demo, as `npm start` gives a newcomer.
  up = await startUp(
    path.join(testInfo.project.outputDir, `armtwin-up-so101-${process.pid}.log`),
    [],
    '',
    { so101: true },
  );
  observer = await ArmObserver.connect(up.mqttUrl, ARM);
  await until(
    () => observer.online === '1' && observer.angles.filter(Number.isFinite).length === 6,
    30_000,
    'the SO-101 online with its six servos read from the bus',
  );
});

test.afterAll(async () => {
  await observer?.close();
  await up?.stop();
});

interface So101Window {
  __armtwin?: {
    ready?: boolean;
    robots: { active: { spec: { name: string } } };
    viewer: {
      meshFailures: readonly { url: string; message: string }[];
      liveRobot: { links: Record<string, unknown> } | null;
    };
  };
}

/** The page on `?arm=so101` (render=main: the live arm's model is on the page only then). */
async function open(page: Page): Promise<string[]> {
  const failed: string[] = [];
  // /api answers 503 here by design: this `up` runs without the middleware (./support/up.ts).
  const mine = (url: string) => !new URL(url).pathname.startsWith('/api/');
  page.on(
    'response',
    (r) => r.status() >= 400 && mine(r.url()) && failed.push(`${r.status()} ${r.url()}`),
  );
  page.on('requestfailed', (r) => failed.push(`${r.failure()?.errorText} ${r.url()}`));
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  await page.goto(`${up.url}?arm=${ARM}&render=main`);
  await page.waitForFunction(() => (window as unknown as So101Window).__armtwin?.ready === true);
  await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
  return failed;
}

const model = (page: Page) =>
  page.evaluate(() => {
    const a = (window as unknown as So101Window).__armtwin!;
    return {
      name: a.robots.active.spec.name,
      links: Object.keys(a.viewer.liveRobot?.links ?? {}).sort(),
      meshFailures: a.viewer.meshFailures.map((f) => f.url),
    };
  });

/** The gripper's angles the gateway reported since `since` (ms epoch), in order. */
function gripperSince(since: number): number[] {
  const seen: number[] = [];
  const reader = createReader({
    onFrame: () => {},
    onGroup: (g) => {
      for (const f of g.frames) if (f.type === 'angle' && f.id === GRIPPER) seen.push(f.deg);
    },
  });
  for (const m of observer.messages)
    if (m.at >= since && m.topic === `arm/${ARM}/status`) reader.feed(m.text);
  return seen;
}

test('so101: the page loads the SO-101, every mesh, and the twin follows the emulated bus', async ({
  page,
}, testInfo) => {
  const meshesAsked: string[] = [];
  page.on('request', (r) => r.url().includes('/models/so101/meshes/') && meshesAsked.push(r.url()));
  const failed = await open(page);
  await expect.poll(async () => (await model(page)).name, { timeout: 30_000 }).toBe('so101');
  await expect.poll(async () => (await model(page)).links.length).toBe(URDF_LINKS.length);
  const m = await model(page);
  expect(m.links).toEqual([...URDF_LINKS].sort());
  expect(m.meshFailures).toEqual([]);
  expect(failed, 'requests that failed').toEqual([]);
  expect(meshesAsked.length).toBeGreaterThan(0);
  await expect(page.getByTestId('mesh-failures')).toBeHidden();
  await expect(page.getByRole('slider')).toHaveCount(6);

  // A move made on the bus side (an MQTT client's, not the page's) is drawn as reported.
  await observer.client.publishAsync(`arm/${ARM}/control`, '#002A-030.00T1000!', { qos: 1 });
  await until(() => observer.angles[2] === -30, 20_000, 'shoulder_lift at -30° on the bus');
  await expect
    .poll(async () => Math.abs((await renderedAngles(page))[1]! + 30), { timeout: 10_000 }) // servo 002, slot 1
    .toBeLessThan(0.5);
  await expect
    .poll(async () => Math.abs((await joints(page))[1]! + (30 * Math.PI) / 180))
    .toBeLessThan(0.01);
  await shot(page, testInfo, 'so101-followed');
});

test('so101: a gripper jog moves the bus servo; a Cartesian move then leaves the gripper where it was', async ({
  page,
}, testInfo) => {
  await open(page);
  await expect.poll(async () => (await model(page)).name, { timeout: 30_000 }).toBe('so101');

  // Jog the gripper (tool joint) to 30°: the emulated servo gets there, read back by the gateway.
  const jogAt = Date.now();
  await page.getByRole('slider', { name: /gripper/i }).fill('30');
  await until(() => observer.angles[GRIPPER] === 30, 20_000, 'the gripper at 30° on the bus');
  expect(observer.commands(jogAt).some((c) => c.includes('#006'))).toBe(true);
  await expect
    .poll(async () => Math.abs((await renderedAngles(page))[GRIPPER - 1]! - 30))
    .toBeLessThan(0.5);

  // A Cartesian target 30 mm below the tip and 20 mm to the side, from where the panel starts.
  const axis = (name: string) => page.getByLabel(name, { exact: true });
  const tip = {
    x: Number(await axis('X').inputValue()),
    y: Number(await axis('Y').inputValue()),
    z: Number(await axis('Z').inputValue()),
  };
  const before = observer.angles.slice(1, 6);
  await axis('Y').fill(String(Math.round(tip.y + 20)));
  await axis('Z').fill(String(Math.round(tip.z - 30)));
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
  const moveAt = Date.now();
  await page.getByRole('button', { name: 'Move' }).click();
  // A numeric-IK arm's Cartesian move goes as a motion request (planned, checked, executed).
  await expect(page.getByTestId('kms-reply')).toContainText('as a motion request');
  // The arm goes: a joint of the IK chain leaves where it was…
  await until(
    () => observer.angles.slice(1, 6).some((deg, i) => Math.abs(deg - before[i]!) > 1),
    20_000,
    'the arm to move',
  );
  // …and comes to rest (the same pose in two reads 1 s apart).
  await expect
    .poll(
      async () => {
        const a = observer.angles.slice(1, 6).join();
        await page.waitForTimeout(1000);
        return observer.angles.slice(1, 6).join() === a;
      },
      { timeout: 30_000 },
    )
    .toBe(true);
  // The gripper never left 30° on the bus during the move (within one encoder step, 360/4096°:
  // the move's goals are written from the positions read, 30° being 341.3 steps), and is drawn there.
  const gripper = gripperSince(moveAt);
  expect(gripper.length).toBeGreaterThan(10);
  expect(Math.max(...gripper.map((deg) => Math.abs(deg - 30)))).toBeLessThanOrEqual(360 / 4096);
  await expect
    .poll(async () => Math.abs((await renderedAngles(page))[GRIPPER - 1]! - 30))
    .toBeLessThan(0.5);
  await shot(page, testInfo, 'so101-cartesian');
});
