/// <reference lib="dom" />
/**
 * One operator at a time, in two pages (docs/protocol.md § Control), on `armtwin up` with a
 * users file (the embedded broker vouches for each name): alice logs in and takes control;
 * bob's page says "Controlled by alice", its move controls are off (the stop is not), and it
 * asks; alice refuses, then grants; the arm follows bob's jog and not alice's page any more;
 * bob's page goes away and alice takes control again; she lets go, takes it once more and her
 * page crashes at once: the arm lets go of her after the holder's lease.
 */
import type { Browser, Page } from '@playwright/test';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { ensureHudBuilt } from './support/build-hud.ts';
import { startUpWithControlUsers, ArmWatcher, demoPassword, type UpProcess } from './support/up.ts';
import { until } from './support/sim.ts';

let up: UpProcess;

// eslint-disable-next-line no-empty-pattern
test.beforeAll(async ({}, testInfo) => {
  test.setTimeout(120_000);
  ensureHudBuilt();
  up = await startUpWithControlUsers('control', testInfo.project.outputDir);
});
test.afterAll(async () => {
  await up?.stop();
});

async function pageAs(browser: Browser, user: string): Promise<Page> {
  const page = await (await browser.newContext()).newPage();
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

const base = (page: Page) => page.getByRole('slider', { name: 'Base', exact: true });
const holderLine = (page: Page) => page.getByTestId('control-holder');

test('two pages: one controls, one watches and asks; refuse, grant, and take back', async ({
  browser,
}, testInfo) => {
  test.setTimeout(90_000);
  const watcher = await ArmWatcher.connect(up.mqttUrl, 'arm1', 'watch');
  const alice = await pageAs(browser, 'alice');
  try {
    // Control is taken on log-in when nobody holds the arm.
    await expect(holderLine(alice)).toHaveText('You control arm1 as alice.');
    await expect(base(alice)).toBeEnabled();

    const bob = await pageAs(browser, 'bob');
    await expect(holderLine(bob)).toHaveText('Controlled by alice');
    await expect(base(bob)).toBeDisabled();
    await expect(bob.getByRole('button', { name: 'Move', exact: true })).toBeDisabled();
    await expect(bob.getByTestId('estop')).toBeEnabled(); // the e-stop is everyone's
    await expect(bob.getByRole('button', { name: 'Take control' })).toHaveCount(0);
    await shot(bob, testInfo, 'control-read-only');

    // A tampered page (its own client, around its disabled controls) still cannot move the arm:
    // the arm refuses bob's move while alice holds it.
    const before = watcher.pwm(0);
    const sentAt = Date.now();
    await bob.evaluate(() => {
      const link = (window as unknown as { __armtwin: { link: { client: unknown } } }).__armtwin
        .link;
      (link.client as { publish(t: string, p: string, o: object): void }).publish(
        'arm/arm1/control/bob',
        '#000P2400T0300!',
        { qos: 1 },
      );
    });
    await until(
      () => watcher.errors.find((e) => e.at >= sentAt && e.text === 'controlled by alice'),
      10_000,
      '$ERR:controlled by alice!',
    );
    const later = watcher.positions.length;
    await until(() => watcher.positions.length > later + 150, 10_000, 'more samples');
    expect(watcher.pwmBetween(0, sentAt, Date.now()).every((p) => Math.abs(p - before) <= 1)).toBe(
      true,
    );

    // bob asks; alice refuses.
    await bob.getByRole('button', { name: 'Ask for control' }).click();
    await expect(bob.getByText('Asked alice; waiting…')).toBeVisible();
    const request = alice.getByRole('list', { name: 'Requests for control' });
    await expect(request).toContainText('bob asks for control');
    await shot(alice, testInfo, 'control-request');
    await request.getByRole('button', { name: 'Refuse' }).click();
    await expect(bob.getByTestId('control-notice')).toHaveText('alice refused control to bob');
    await expect(holderLine(bob)).toHaveText('Controlled by alice');

    // bob asks again; alice grants: the controls change sides.
    await bob.getByRole('button', { name: 'Ask for control' }).click();
    await request.getByRole('button', { name: 'Grant' }).click();
    await expect(holderLine(bob)).toHaveText('You control arm1 as bob.');
    await expect(base(bob)).toBeEnabled();
    await expect(holderLine(alice)).toHaveText('Controlled by bob');
    await expect(base(alice)).toBeDisabled();

    // bob's jog reaches the arm.
    const start = watcher.pwm(0);
    await base(bob).fill('60');
    await until(
      () => Math.abs(watcher.pwm(0) - start) > 100,
      15_000,
      "the arm to follow bob's jog",
    );

    // bob's page goes away: the arm is free again, and alice takes it back.
    await bob.context().close();
    await expect(holderLine(alice)).toHaveText('Nobody controls arm1.', { timeout: 15_000 });
    await alice.getByRole('button', { name: 'Take control' }).click();
    await expect(holderLine(alice)).toHaveText('You control arm1 as alice.');
    await expect(base(alice)).toBeEnabled();
    await shot(alice, testInfo, 'control-taken-back');

    // alice lets go, takes control again, and her page crashes at once (its connection dies with
    // it). Her lease runs from her first beat (a holder that never beats is never timed out), and
    // the page sends that beat with the take: the arm lets go of her after the lease.
    const said: string[] = [];
    watcher.client.on('message', (t, payload) => {
      if (t === 'arm/arm1/audit') said.push(payload.toString());
    });
    await watcher.client.subscribeAsync('arm/arm1/audit', { qos: 0 });
    await alice.getByRole('button', { name: 'Release control' }).click();
    await expect(holderLine(alice)).toHaveText('Nobody controls arm1.');
    const cdp = await alice.context().newCDPSession(alice);
    await alice.getByRole('button', { name: 'Take control' }).click();
    void cdp.send('Page.crash').catch(() => {}); // never answers: the page is gone
    await until(
      () => said.some((e) => /"kind":"lost"/.test(e) && /"by":"alice"/.test(e)),
      10_000,
      'the arm letting go of alice',
    ).catch((e: unknown) => {
      throw new Error(`${String(e)}; the arm's audit said: ${said.join(' | ')}`);
    });
  } finally {
    await alice.context().close();
    await watcher.close();
  }
});
