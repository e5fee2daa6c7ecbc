/// <reference lib="dom" />
/**
 * A robot imported from the page: an operator gives `armtwin up` (log-ins on, an empty models
 * folder) a zip of rtb-data's ABB IRB 140 package as it is shipped (`package://` paths, STL
 * meshes) through the Import panel's file input; the server imports it with `armtwin robot
 * import`'s core and serves it at once; a simulated arm started on it is drawn with every mesh.
 * Something that is not a robot, dropped on the page, is refused with the reason shown; a
 * viewer's import is refused by the server.
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { RTB_ROBOTS, rtbDataDir } from '../helpers/rtb-data.ts';
import { armtwin, type Child } from '../integration/sim-helpers.ts';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUp, type UpProcess } from './support/up.ts';

interface ImportWindow {
  __armtwin?: {
    robots: { active: { spec: { name: string } } };
    joints(): number[];
    viewer: { meshFailures: readonly { url: string; message: string }[] };
  };
}

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-drop-'));
const models = path.join(dir, 'models');
const zip = path.join(dir, 'abb_irb140_description.zip');
let up: UpProcess;
let sim: Child | undefined;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  fs.mkdirSync(models);
  const pkg = path.dirname(path.dirname(path.join(rtbDataDir(), RTB_ROBOTS.irb140)));
  execFileSync('python3', [
    '-c',
    'import shutil, sys; shutil.make_archive(sys.argv[1][:-4], "zip", sys.argv[2])',
    zip,
    pkg,
  ]);
  up = await startUp(path.join(testInfo.project.outputDir, `armtwin-up-drop-${process.pid}.log`), [
    '--models',
    models,
  ]);
});

test.afterAll(async () => {
  await sim?.stop();
  await up?.stop();
  fs.rmSync(dir, { recursive: true, force: true });
});

async function open(page: Page, user: string, arm = 'arm1') {
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  await page.goto(`${up.url}?arm=${arm}`);
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill(user);
  await form.getByLabel('Password').fill(demoPassword(user));
  await form.getByRole('button', { name: 'Log in' }).click();
  await expect(page.getByText(`Signed in as ${user}, ${user}.`)).toBeVisible();
}

test('something that is not a robot, dropped on the page, is refused with the reason', async ({
  page,
}) => {
  await open(page, 'operator');
  const panel = page.getByTestId('import');
  const data = await page.evaluateHandle(() => {
    const dt = new DataTransfer();
    dt.items.add(new File(['just a note'], 'notes.txt', { type: 'text/plain' }));
    return dt;
  });
  await page.locator('#view').dispatchEvent('dragover', { dataTransfer: data });
  await page.locator('#view').dispatchEvent('drop', { dataTransfer: data });
  await expect(panel.getByTestId('import-error')).toContainText(
    'no .urdf file in the dropped files',
  );
  expect(fs.readdirSync(models)).toEqual([]);
});

test('a zipped robot package is imported from the page and drawn with every mesh', async ({
  page,
}, testInfo) => {
  test.setTimeout(120_000);
  await open(page, 'operator');
  const panel = page.getByTestId('import');
  await panel.locator('summary').click();
  // the package holds two URDFs (irb140.urdf, irb140QT.urdf): name the one to import
  await panel.getByLabel('which .urdf').fill('irb140.urdf');
  await panel.getByLabel('name', { exact: true }).fill('irb140');
  await panel.getByLabel('.zip or files').setInputFiles(zip);
  await expect(panel.getByTestId('import-result')).toContainText('Imported irb140', {
    timeout: 30_000,
  });
  expect(fs.existsSync(path.join(models, 'irb140', 'profile.json'))).toBe(true);
  await shot(page, testInfo, 'imported');

  // an arm on the new robot, served from disk without a rebuild
  sim = armtwin(
    ['sim', '--profile', 'irb140', '--models', models, '--mqtt', up.mqttUrl, '--arm', 'arm2'],
    { MQTT_USERNAME: 'arm2', MQTT_PASSWORD: demoPassword('arm2') },
  );
  const arm = await page.context().newPage();
  await open(arm, 'viewer', 'arm2');
  const state = () =>
    arm.evaluate(() => {
      const a = (window as unknown as ImportWindow).__armtwin!;
      return {
        name: a.robots.active.spec.name,
        joints: a.joints().length,
        failures: a.viewer.meshFailures.map((f) => f.message),
      };
    });
  await expect.poll(async () => (await state()).name, { timeout: 30_000 }).toBe('irb140');
  await expect.poll(async () => (await state()).joints, { timeout: 30_000 }).toBe(6);
  expect((await state()).failures).toEqual([]);
  await expect(arm.getByTestId('mesh-failures')).toBeHidden();
  await shot(arm, testInfo, 'irb140');
});

test('a viewer may not import a robot', async () => {
  const res = await fetch(new URL('api/robots/import?name=other', up.url), {
    method: 'POST',
    headers: {
      'content-type': 'application/zip',
      authorization: `Basic ${Buffer.from(`viewer:${demoPassword('viewer')}`).toString('base64')}`,
    },
    body: fs.readFileSync(zip),
  });
  expect(res.status).toBe(403);
  expect(fs.existsSync(path.join(models, 'other'))).toBe(false);
});
