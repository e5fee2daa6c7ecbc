/// <reference lib="dom" />
/**
 * The calibration wizard on a simulated servo bus, end to end. The "real" arm is `armtwin sim
 * --bus dynamixel` running `calib-truth` (the elbow, 002, mounted as it really is: its joint is
 * the raw servo angle − 15°); the bus gateway and the HUD run `calib-arm`, whose elbow is
 * wrong both ways (polarity −1, offset +20°), so the twin shows the elbow 35° off and turning the
 * wrong way. `armtwin up` (with log-ins) serves the HUD and writes the profile. An operator walks
 * the wizard: jogs the elbow to its zero, then the positive way, then across its travel, and the
 * ghost shows the joint as the new calibration reads it over the live (wrong) twin. Saved: the
 * profile file holds the corrected polarity, offset and limits (old one backed up), the gateway
 * takes it without a restart and the twin's elbow stands where the real one is. A viewer's
 * write is refused.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { REPO_ROOT } from '../helpers/services.ts';
import { armtwin, type Child } from '../integration/sim-helpers.ts';
import { serialLine } from '../integration/serial-line.ts';
import { expect, shot, test } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { demoPassword, startUp, type UpProcess } from './support/up.ts';

interface CalibWindow {
  __armtwin?: {
    ready?: boolean;
    joints(which?: 'robot' | 'ghost'): number[];
    robots: { active: { spec: { name: string } } };
  };
}

const ARM = 'arm2'; // the sample users file's second device
const ELBOW = 2;
const DEG = Math.PI / 180;

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-calib-'));
const models = path.join(dir, 'models');
const armFile = path.join(models, 'calib-arm', 'profile.json');
let up: UpProcess;
let gateway: Child | undefined;
const line = serialLine(
  path.join(dir, 'host'),
  path.join(dir, 'arm'),
  (armSide) => [
    'sim',
    '--bus',
    'dynamixel',
    '--serial',
    armSide,
    '--profile',
    'calib-truth',
    '--models',
    models,
  ],
  'simulated servo bus on the serial line',
);

/** armtwin5 as a bus arm whose elbow is a bus servo with these fields. */
function writeProfile(name: string, elbow: Record<string, unknown>): void {
  const src = path.join(REPO_ROOT, 'public/models/armtwin5');
  const to = path.join(models, name);
  fs.cpSync(src, to, { recursive: true });
  const raw = JSON.parse(fs.readFileSync(path.join(src, 'profile.json'), 'utf8')) as {
    name: string;
    servos: Record<string, unknown>[];
  };
  raw.name = name;
  raw.servos[ELBOW] = { ...raw.servos[ELBOW], units: 'angle', min: -150, max: 150, ...elbow };
  fs.writeFileSync(path.join(to, 'profile.json'), JSON.stringify(raw, null, 2));
}

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(180_000);
  ensureHudBuilt();
  writeProfile('calib-truth', { polarity: 1, offset: -15 });
  writeProfile('calib-arm', { polarity: -1, offset: 20 });
  up = await startUp(path.join(testInfo.project.outputDir, `armtwin-up-calib-${process.pid}.log`), [
    '--models',
    models,
  ]);
  await line.start();
  gateway = armtwin(
    [
      'gateway',
      '--bus',
      'dynamixel',
      '--serial',
      line.hostSide,
      '--profile',
      'calib-arm',
      '--models',
      models,
      '--mqtt',
      up.mqttUrl,
      '--arm',
      ARM,
      // only a `0` (a page let go) holds the arm: a beat late under load would stop a jog
      // half-way; the deadman's lease has its own test (deadman.spec.ts)
      '--operator-lease',
      '0',
    ],
    { MQTT_USERNAME: ARM, MQTT_PASSWORD: demoPassword(ARM) },
  );
});

// eslint-disable-next-line no-empty-pattern
test.afterAll(async ({}, testInfo) => {
  await gateway?.stop();
  if (gateway)
    fs.writeFileSync(
      path.join(testInfo.project.outputDir, `gateway-calib-${process.pid}.log`),
      gateway.output(),
    );
  await line.stop();
  await up?.stop();
  fs.rmSync(dir, { recursive: true, force: true });
});

async function open(page: Page, user: string) {
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  // The page's deadman keep-alive long (60 s): on this 2-core machine under the whole suite, a
  // renderer stall of over 1.5 × the default 2 s let the broker's will `0` stop the elbow
  // half-way through a jog (a fresh clone: the elbow stopped at −31.9° of −45°, and the gateway
  // counted two deadman stops in a test whose page's close accounts for one).
  // Letting go on a stalled page is the deadman's job, tested in deadman.spec.ts; here the lease
  // is off (`--operator-lease 0`) for the same reason.
  await page.goto(`${up.url}?arm=${ARM}&keepalive=60`);
  await page.waitForFunction(() => (window as unknown as CalibWindow).__armtwin?.ready === true);
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill(user);
  await form.getByLabel('Password').fill(demoPassword(user));
  await form.getByRole('button', { name: 'Log in' }).click();
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as CalibWindow).__armtwin!.robots.active.spec.name),
    )
    .toBe('calib-arm');
}

/** The elbow's drawn joint angle, degrees, on the live twin or the ghost. */
const elbow = (page: Page, which: 'robot' | 'ghost' = 'robot') =>
  page
    .evaluate(([w, i]) => (window as unknown as CalibWindow).__armtwin!.joints(w)[i]!, [
      which,
      ELBOW,
    ] as const)
    .then((rad) => rad / DEG);

test('the wizard finds the elbow’s zero, direction and travel, and the twin follows', async ({
  page,
}, testInfo) => {
  test.setTimeout(120_000);
  await open(page, 'operator');
  // the real elbow is at joint −15° (raw 0°); the wrong profile draws it at +20°
  await expect.poll(() => elbow(page)).toBeCloseTo(20, 1);

  const panel = page.getByTestId('calibration');
  await panel.locator('summary').click();
  await panel.getByRole('combobox').selectOption({ label: '002 Elbow' });
  const reading = panel.getByTestId('calibration-reading');
  await expect(reading).toHaveText('0.00°');
  const jog = async (deg: number, times: number) => {
    const name = `Jog ${deg > 0 ? '+' : '−'}${Math.abs(deg)}°`;
    for (let k = 0; k < times; k++) await panel.getByRole('button', { name }).click();
  };

  // 1. zero: the ghost shows the elbow at 0; the real joint is at 0 when the servo reads −15
  await expect.poll(() => elbow(page, 'ghost')).toBeCloseTo(0, 1);
  await jog(-10, 1);
  await jog(-1, 5);
  await expect(reading).toHaveText('-15.00°', { timeout: 20_000 });
  await panel.getByRole('button', { name: 'Zero is here' }).click();

  // 2. direction: the ghost leans +30°; the real joint gets there as the reading falls
  await expect.poll(() => elbow(page, 'ghost')).toBeCloseTo(30, 1);
  await jog(-10, 3);
  await expect(reading).toHaveText('-45.00°', { timeout: 20_000 });
  await panel.getByRole('button', { name: 'It leans like the ghost' }).click();

  // 3. travel: up to a reading of +15 (joint −30°), down to −105 (joint +90°)
  await jog(10, 6);
  await expect(reading).toHaveText('15.00°', { timeout: 20_000 });
  await jog(-10, 12);
  await expect(reading).toHaveText('-105.00°', { timeout: 30_000 });
  // (a servo just leaving its goal's tick reads that tick's angle: 15.03°, not 15.00°)
  await expect(panel.getByTestId('calibration-travel')).toHaveText(
    /^travel -105\.0\d° … 15\.0\d°$/,
  );
  // the check: the ghost stands where the real elbow is (90°), the twin still says −85°
  await expect.poll(() => elbow(page, 'ghost')).toBeCloseTo(90, 1);
  expect(await elbow(page)).toBeCloseTo(-85, 1);
  await panel.getByRole('button', { name: 'Travel recorded' }).click();

  // 4. review and save
  const shown = async (field: string) =>
    Number(await panel.getByTestId(`calibration-new-${field}`).textContent());
  await expect(panel.getByTestId('calibration-new-polarity')).toHaveText('1');
  expect(await shown('offset')).toBe(-15);
  expect(await shown('min')).toBeCloseTo(-30, 1);
  expect(await shown('max')).toBeCloseTo(90, 1);
  await shot(page, testInfo, 'calibration-review');
  await panel.getByRole('button', { name: 'Save to profile' }).click();
  await expect(panel.getByTestId('calibration-in-force')).toBeAttached({ timeout: 15_000 });

  // the file holds the corrected elbow, the rest as it was, and the old one is kept
  const saved = JSON.parse(fs.readFileSync(armFile, 'utf8')) as {
    servos: Record<string, unknown>[];
  };
  const elbowSaved = saved.servos[ELBOW]!;
  expect(elbowSaved).toMatchObject({ id: '002', units: 'angle', polarity: 1, offset: -15 });
  expect(elbowSaved.min).toBeCloseTo(-30, 1);
  expect(elbowSaved.max).toBeCloseTo(90, 1);
  const backups = fs.readdirSync(path.dirname(armFile)).filter((f) => f.endsWith('.bak'));
  expect(backups).toHaveLength(1);
  const old = JSON.parse(fs.readFileSync(path.join(path.dirname(armFile), backups[0]!), 'utf8'));
  expect(old.servos[ELBOW]).toMatchObject({ polarity: -1, offset: 20 });

  // the gateway took it without a restart: the twin's elbow is where the real one is
  await expect.poll(() => elbow(page), { timeout: 15_000 }).toBeCloseTo(90, 0);
  // and it moves the right way now: a jog of +10° of the new calibration is +10° of joint
  await panel.getByRole('button', { name: 'Calibrate again' }).click();
  await jog(-10, 1);
  await expect.poll(() => elbow(page), { timeout: 15_000 }).toBeCloseTo(80, 0);
  await shot(page, testInfo, 'calibration-in-force');
});

test('a viewer may not write a calibration', async ({ page }) => {
  await open(page, 'viewer');
  const panel = page.getByTestId('calibration');
  await panel.locator('summary').click();
  await expect(panel.getByRole('status').first()).toContainText(/view|operator/i);
  await expect(panel.getByRole('button', { name: 'Torque off' })).toHaveCount(0);
  const before = fs.readFileSync(armFile, 'utf8');
  const res = await fetch(new URL('api/robots/calib-arm/calibration', up.url), {
    method: 'PUT',
    headers: {
      'content-type': 'application/json',
      authorization: `Basic ${Buffer.from(`viewer:${demoPassword('viewer')}`).toString('base64')}`,
    },
    body: JSON.stringify({ servos: [{ id: 2, polarity: 1, offset: 0, min: -9, max: 9 }] }),
  });
  expect(res.status).toBe(403);
  expect(fs.readFileSync(armFile, 'utf8')).toBe(before);
});

test('torque off leaves the elbow limp (a jog does not move it), torque on holds it again', async ({
  page,
}) => {
  await open(page, 'operator');
  const panel = page.getByTestId('calibration');
  await panel.locator('summary').click();
  await panel.getByRole('combobox').selectOption({ label: '002 Elbow' });
  const reading = async () =>
    parseFloat((await panel.getByTestId('calibration-reading').textContent()) ?? '');
  await expect.poll(reading).not.toBeNaN();
  const before = await reading();
  const messages = () =>
    page.evaluate(
      () =>
        (window as unknown as { __armtwin: { store: { counters: { messages: number } } } })
          .__armtwin.store.counters.messages,
    );

  await panel.getByRole('button', { name: 'Torque off' }).click();
  await expect(panel.getByTestId('torque-state')).toContainText('Torque off');
  await panel.getByRole('button', { name: 'Jog −10°' }).click();
  // 100 more state reports (a 10° jog takes 0.7 s; that is 2 s at 50 Hz): it has not moved
  const m0 = await messages();
  await expect.poll(messages, { timeout: 15_000 }).toBeGreaterThan(m0 + 100);
  expect(await reading()).toBeCloseTo(before, 1);

  await panel.getByRole('button', { name: 'Torque on' }).click();
  await expect(panel.getByTestId('torque-state')).toContainText('Torque on');
  await panel.getByRole('button', { name: 'Jog −10°' }).click();
  await expect.poll(reading, { timeout: 15_000 }).toBeCloseTo(before - 10, 1);
});
