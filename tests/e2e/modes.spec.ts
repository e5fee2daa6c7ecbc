/// <reference lib="dom" />
/**
 * Model / Shadow / Twin (issue 20, docs/protocol.md § Modes) on `armtwin up` with a users file:
 *  1. a plan rehearsed in Model mode moves only the model copy `arm1-model` (a subscriber on
 *     the real arm's control topics hears nothing while the copy reaches the last waypoint); then
 *     `Run on arm` runs it on arm1, which reaches the last waypoint, and the page shows predicted
 *     vs actual per servo;
 *  2. Shadow mode turns every control in the panels off, and the stop still reaches the arm;
 *  3. the mode switch is on screen in every panel and tab state, the phone layout included.
 */
import fs from 'node:fs';
import path from 'node:path';
import mqtt, { type MqttClient } from 'mqtt';
import type { Browser, Locator, Page } from '@playwright/test';
import { parseProfile } from '@armtwin/robot';
import { createMotionRobot, tipPose } from '@armtwin/motion';
import { REPO_ROOT } from '../helpers/services.ts';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { startUpWithControlUsers, ArmWatcher, demoPassword, type UpProcess } from './support/up.ts';
import { onScreen } from './support/on-screen.ts';

let up: UpProcess;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  up = await startUpWithControlUsers('modes', testInfo.project.outputDir);
});
test.afterAll(async () => {
  await up?.stop();
});

const profile = parseProfile(
  JSON.parse(fs.readFileSync(path.join(REPO_ROOT, 'public/models/armtwin5/profile.json'), 'utf8')),
);
if (!profile.ok) throw new Error(profile.errors.join('; '));
const ROBOT = createMotionRobot(profile.profile);
const LAST = { x: 200, y: 0, z: 150 };

/** Everything published on the real arm's control topics (plain and per user). */
class ControlSpy {
  readonly seen: { at: number; topic: string; payload: string }[] = [];
  private constructor(readonly client: MqttClient) {}
  static async connect(url: string): Promise<ControlSpy> {
    // The arm's own device account: the one role that may read its control topics.
    const client = await mqtt.connectAsync(url, {
      username: 'arm1',
      password: demoPassword('arm1'),
      clientId: `e2e-spy-${process.pid}-${Date.now()}`,
    });
    const spy = new ControlSpy(client);
    client.on('message', (topic, payload) =>
      spy.seen.push({ at: Date.now(), topic, payload: payload.toString() }),
    );
    await client.subscribeAsync(['arm/arm1/control', 'arm/arm1/control/+'], { qos: 1 });
    return spy;
  }
  since(at: number) {
    return this.seen.filter((m) => m.at >= at);
  }
  close() {
    return this.client.endAsync(true);
  }
}

async function pageAs(
  browser: Browser,
  user: string,
  options: Parameters<Browser['newContext']>[0] = {},
): Promise<Page> {
  const page = await (await browser.newContext(options)).newPage();
  page.on('pageerror', (err) => console.error(`[page error ${user}] ${err.message}`));
  await page.goto(up.url);
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  const form = page.getByRole('form', { name: 'Log in' });
  await form.getByLabel('Username').fill(user);
  await form.getByLabel('Password').fill(demoPassword(user));
  await form.getByRole('button', { name: 'Log in' }).click();
  await expect(page.getByTestId('signed-in-as')).toContainText(`Signed in as ${user}`);
  await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
  return page;
}

interface ModesWindow {
  __armtwin?: {
    joints(which?: 'robot' | 'ghost' | 'sibling'): number[];
    replay: { active: boolean; record: unknown };
    recorder: { errors: { maxDeg: number; meanDeg: number }[] | null };
  };
}
const joints = (page: Page, which: 'robot' | 'sibling') =>
  page.evaluate((w) => (window as unknown as ModesWindow).__armtwin!.joints(w), which);

const modeButton = (page: Page, name: 'Model' | 'Shadow' | 'Twin') =>
  page.getByRole('group', { name: 'Mode' }).getByRole('button', { name, exact: true });

const tipError = (w: ArmWatcher) => {
  const pwm = [0, 1, 2, 3, 4, 5].map((id) => w.pwm(id));
  if (pwm.some((p) => !Number.isFinite(p))) return Infinity;
  const tip = tipPose(ROBOT, pwm);
  return Math.hypot(tip.x - LAST.x, tip.y - LAST.y, tip.z - LAST.z);
};

/** Two waypoints by number, a Cartesian path: (150, 0, 250) → (200, 0, 150). */
async function twoWaypoints(page: Page): Promise<void> {
  const add = page.getByRole('button', { name: 'Add waypoint at tip' });
  await add.click();
  await add.click();
  const set = async (n: number, x: number, y: number, z: number) => {
    await page.getByLabel(`Waypoint ${n} X`).fill(String(x));
    await page.getByLabel(`Waypoint ${n} Y`).fill(String(y));
    await page.getByLabel(`Waypoint ${n} Z`).fill(String(z));
  };
  await set(1, 150, 0, 250);
  await set(2, LAST.x, LAST.y, LAST.z);
  await page.getByRole('radio', { name: 'Cartesian path' }).check();
}

test('rehearse in Model mode (only the copy moves), then Run on arm: predicted vs actual', async ({
  browser,
}, testInfo) => {
  test.setTimeout(120_000);
  const spy = await ControlSpy.connect(up.mqttUrl);
  const arm = await ArmWatcher.connect(up.mqttUrl, 'arm1', 'watch');
  const copy = await ArmWatcher.connect(up.mqttUrl, 'arm1-model', 'watch');
  const page = await pageAs(browser, 'alice');
  try {
    // An operator opens in Twin.
    await expect(modeButton(page, 'Twin')).toHaveAttribute('aria-pressed', 'true');
    await modeButton(page, 'Model').click();
    await expect(modeButton(page, 'Model')).toHaveAttribute('aria-pressed', 'true');
    await expect(page.getByTestId('mode-note')).toContainText('Commands go to the copy arm1-model');
    expect(new URL(page.url()).searchParams.get('mode')).toBe('model');
    const quietFrom = Date.now();
    // The copy runs and reports, at the real arm's pose.
    await expect.poll(() => copy.positions.length, { timeout: 20_000 }).toBeGreaterThan(10);
    const armStart = tipError(arm);

    await twoWaypoints(page);
    const execute = page.getByRole('button', { name: 'Execute', exact: true });
    await expect(execute).toBeEnabled({ timeout: 10_000 });
    await execute.click();
    await expect(page.getByTestId('plan-run')).toHaveText(/^Done/, { timeout: 30_000 });
    // The copy reaches the last waypoint; the arm's control topics heard nothing, and it stood.
    await expect.poll(() => tipError(copy), { timeout: 10_000 }).toBeLessThan(3);
    expect(spy.since(quietFrom)).toEqual([]);
    expect(Math.abs(tipError(arm) - armStart)).toBeLessThan(1);
    await expect(page.getByTestId('rehearsal')).toContainText('Rehearsal kept');
    // The copy is drawn (the translucent sibling) where it went, the arm where it stands.
    await expect
      .poll(async () => {
        const [robot, sibling] = await Promise.all([
          joints(page, 'robot'),
          joints(page, 'sibling'),
        ]);
        return Math.max(...robot.map((v, i) => Math.abs(v - (sibling[i] ?? NaN))));
      })
      .toBeGreaterThan(0.2);
    await shot(page, testInfo, 'modes-rehearsed');

    // Run on arm: Twin again, the same plan on arm1, which reaches the last waypoint.
    const runFrom = Date.now();
    await page.getByRole('button', { name: 'Run on arm', exact: true }).click();
    await expect(modeButton(page, 'Twin')).toHaveAttribute('aria-pressed', 'true');
    await expect(page.getByTestId('plan-run')).toHaveText(/^Done/, { timeout: 30_000 });
    await expect.poll(() => tipError(arm), { timeout: 10_000 }).toBeLessThan(3);
    const groups = spy.since(runFrom).filter((m) => m.payload.startsWith('{#'));
    expect(groups.length).toBeGreaterThan(10);
    expect(groups.every((m) => m.topic === 'arm/arm1/control/alice')).toBe(true);

    // Predicted vs actual: one row per servo, the moving ones compared (finite errors).
    const table = page.getByTestId('predicted-vs-actual');
    await expect(table).toBeVisible();
    await expect(table.getByRole('row')).toHaveCount(1 + 6);
    const base = table.getByRole('row', { name: /^Base/ });
    await expect(base.getByRole('cell').first()).toHaveText(/^\d+\.\d\d$/);
    await shot(page, testInfo, 'modes-predicted-vs-actual');
    const errors = await page.evaluate(() =>
      (window as unknown as ModesWindow).__armtwin!.recorder.errors!.map(
        (e) => `${e.maxDeg.toFixed(2)}/${e.meanDeg.toFixed(2)}`,
      ),
    );
    console.log(`modes e2e: predicted vs actual per servo, max/mean °: ${errors.join(', ')}`);

    // Replay run: the actual run plays as the replay's sibling, the rehearsal as the ghost.
    const replayButton = page.getByRole('button', { name: 'Replay run', exact: true });
    await replayButton.click();
    await expect(replayButton).toHaveAttribute('aria-pressed', 'true');
    expect(
      await page.evaluate(() => {
        const r = (window as unknown as ModesWindow).__armtwin!.replay;
        return r.active && r.record !== null;
      }),
    ).toBe(true);

    // Back in Model mode a jog moves the copy (whose pose the slider shows), not the arm.
    await modeButton(page, 'Model').click();
    await expect(page.getByTestId('mode-note')).toContainText('Commands go to the copy');
    const jogFrom = Date.now();
    const armBase = arm.pwm(0);
    const copyBase = copy.pwm(0);
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('60');
    await expect
      .poll(() => Math.abs(copy.pwm(0) - copyBase), { timeout: 10_000 })
      .toBeGreaterThan(100);
    expect(spy.since(jogFrom)).toEqual([]);
    expect(Math.abs(arm.pwm(0) - armBase)).toBeLessThanOrEqual(1);

    // The stop wins over the mode: pressed in Model mode it reaches the real arm as well.
    const stopFrom = Date.now();
    await page.getByTestId('estop').click();
    await expect
      .poll(() => spy.since(stopFrom).map((m) => `${m.topic} ${m.payload}`), { timeout: 10_000 })
      .toContain('arm/arm1/control/alice #255PDST!');
  } finally {
    await page.context().close();
    await Promise.all([spy.close(), arm.close(), copy.close()]);
  }
});

/**
 * Every button, input, select and textarea in the panels still enabled: the sheet's fold handle
 * and the panels that act on no arm (Log-in, Connection, History: `data-mode-free`) aside.
 */
const enabledControls = (page: Page) =>
  page.evaluate(() =>
    Array.from(
      document.querySelectorAll<HTMLElement>(
        '.hud-sheet button, .hud-sheet input, .hud-sheet select, .hud-sheet textarea',
      ),
    )
      .filter(
        (e) =>
          !e.matches(':disabled') &&
          !e.classList.contains('sheet-handle') &&
          !e.closest('[data-mode-free]'),
      )
      .map((e) => e.getAttribute('aria-label') || e.textContent?.trim() || e.tagName),
  );

test('Shadow mode turns every control off but the stop, which still reaches the arm', async ({
  browser,
}, testInfo) => {
  test.setTimeout(90_000);
  const spy = await ControlSpy.connect(up.mqttUrl);
  const page = await pageAs(browser, 'alice');
  try {
    const slider = page.getByRole('slider', { name: 'Base', exact: true });
    await expect(slider).toBeEnabled();
    expect((await enabledControls(page)).length).toBeGreaterThan(5);

    await modeButton(page, 'Shadow').click();
    await expect(modeButton(page, 'Shadow')).toHaveAttribute('aria-pressed', 'true');
    await expect(page.getByTestId('mode-note')).toContainText('Shadow mode');
    expect(await enabledControls(page)).toEqual([]);
    await expect(slider).toBeDisabled();
    // The stop and the mode switch stay on.
    await expect(page.getByTestId('estop')).toBeEnabled();
    await expect(modeButton(page, 'Twin')).toBeEnabled();
    await shot(page, testInfo, 'modes-shadow');

    const from = Date.now();
    await page.getByTestId('estop').click();
    await expect
      .poll(() => spy.since(from).map((m) => `${m.topic} ${m.payload}`), { timeout: 10_000 })
      .toContain('arm/arm1/control/alice #255PDST!');
    // Nothing else went out in Shadow mode (no pings, no moves).
    expect(spy.since(from).every((m) => m.payload === '#255PDST!')).toBe(true);

    await modeButton(page, 'Twin').click();
    await expect(slider).toBeEnabled();
  } finally {
    await page.context().close();
    await spy.close();
  }
});

async function expectSwitchOnScreen(page: Page, where: string): Promise<void> {
  for (const name of ['Model', 'Shadow', 'Twin'] as const) {
    const b: Locator = modeButton(page, name);
    await expect(b, `${name} in ${where}`).toBeVisible();
    const s = await onScreen(b);
    expect(s.inside && s.uncovered, `${name} on screen in ${where} (on top: ${s.onTop})`).toBe(
      true,
    );
  }
}

test('the mode switch is on screen in every panel and tab state, on a phone too', async ({
  browser,
}) => {
  test.setTimeout(90_000);
  const wide = await pageAs(browser, 'alice');
  try {
    await expectSwitchOnScreen(wide, 'the wide layout');
    await wide.getByText('History', { exact: true }).first().click(); // unfold a folded panel
    await expectSwitchOnScreen(wide, 'the wide layout, History unfolded');
  } finally {
    await wide.context().close();
  }
  const phone = await (
    await browser.newContext({
      viewport: { width: 390, height: 844 },
      hasTouch: true,
      isMobile: true,
    })
  ).newPage();
  try {
    await phone.goto(up.url);
    await phone.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
    await expectSwitchOnScreen(phone, 'the phone layout, sheet lowered');
    for (const tab of ['jog', 'target', 'view', 'arm', 'setup']) {
      await phone.getByTestId(`tab-${tab}`).click();
      await expect(phone.getByTestId(`tab-${tab}`)).toHaveAttribute('aria-expanded', 'true');
      await expectSwitchOnScreen(phone, `the phone layout, tab ${tab}`);
    }
  } finally {
    await phone.context().close();
  }
});
