/// <reference lib="dom" />
/**
 * Keep-out zones edited in the HUD (docs/protocol.md, "Keep-out zones"): under `armtwin up` an
 * operator adds a table in the Ghost panel's folded "Keep-out zones" section; it is written into
 * the robot's profile.json (the one source of truth), the simulator takes it and announces it,
 * the 3D view draws it and a target through it is refused. A zone with nonsense in it is not
 * saved and says why; Remove takes a zone out again.
 */
import fs from 'node:fs';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUpWithProfile, type UpProcess } from './support/up.ts';

const PROFILE = 'zoned5';
let up: UpProcess & { file: string };
const file = () => up.file;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  up = await startUpWithProfile(PROFILE, testInfo.project.outputDir);
});

test.afterAll(async () => {
  await up?.stop();
});

interface ZonesWindow {
  __armtwin: {
    viewer: { zones: { names: string[] } };
    robots: { active: { spec: { name: string } } };
  };
}

test('an operator adds a table in the HUD: saved to the profile, drawn, and in force', async ({
  page,
}, testInfo) => {
  await page.goto(`${up.url}?arm=arm1`);
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  const login = page.getByRole('form', { name: 'Log in' });
  await login.getByLabel('Username').fill('operator');
  await login.getByLabel('Password').fill(demoPassword('operator'));
  await login.getByRole('button', { name: 'Log in' }).click();
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.robots.active.spec.name),
    )
    .toBe(PROFILE);

  const section = page.getByTestId('zones-section');
  await section.getByText('Keep-out zones').click();
  const form = section.getByRole('form', { name: 'Add a keep-out zone' });
  // Nonsense first: the server's parser names the zone and the field, nothing is saved.
  await form.getByLabel('Name').fill('bad');
  const fields = { 'min x': '150', 'min y': '-150', 'min z': '-20', 'max x': '100' };
  for (const [f, v] of Object.entries({ ...fields, 'max y': '150', 'max z': '30' }))
    await form.getByLabel(f, { exact: true }).fill(v);
  await form.getByRole('button', { name: 'Add zone' }).click();
  await expect(section.getByTestId('zones-note')).toContainText(
    'keepOut.zones[0] "bad".max: must be above min on every axis',
  );
  expect(JSON.parse(fs.readFileSync(file(), 'utf8')).keepOut).toBeUndefined();

  await form.getByLabel('Name').fill('table');
  await form.getByLabel('max x', { exact: true }).fill('400');
  await form.getByRole('button', { name: 'Add zone' }).click();
  // The refusal above reads "not saved (…)": wait for this zone's own answer.
  await expect(section.getByTestId('zones-note')).toContainText('Zone "table": saved;');
  expect(JSON.parse(fs.readFileSync(file(), 'utf8')).keepOut.zones).toEqual([
    { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] },
  ]);
  // Back from the arm's announcement: listed, drawn, and checked.
  await expect(section.getByTestId('zone-item')).toHaveCount(1);
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.zones.names),
    )
    .toEqual(['table']);
  await page.getByLabel('X', { exact: true }).fill('250');
  await page.getByLabel('Y', { exact: true }).fill('0');
  await page.getByLabel('Z', { exact: true }).fill('10');
  await expect(page.getByTestId('ik-preview')).toContainText('into zone "table" (code 25)');
  await shot(page, testInfo, 'zone-added');

  await section.getByRole('button', { name: 'Remove zone table' }).click();
  await expect(section.getByTestId('zone-item')).toHaveCount(0);
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.zones.names),
    )
    .toEqual([]);
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
});
