/// <reference lib="dom" />
/**
 * Several brokers in the page (docs/protocol.md § Several brokers): the HUD is given two
 * WebSocket brokers (two real Mosquittos) and `armtwin sim` the same two. The Status panel says
 * "Broker 1 of 2"; the first broker hangs while the operator clicks "Take control" and the e-stop,
 * then is killed: the page says "Broker 2 of 2", its data is live again, the e-stop reaches the
 * second broker and the take does not (nobody controls the arm), and a move sent on the second
 * broker shows on the page's arm; the first comes back: the
 * page goes back to it ("Broker 1 of 2") and the arm is live there too.
 */
import mqtt from 'mqtt';
import { test as base, expect } from '@playwright/test';
import { startMosquitto, type MosquittoService } from '../helpers/services.ts';
import { ensureHudBuilt, HUD_DIST } from './support/build-hud.ts';
import { serveStatic, type StaticServer } from './support/static-server.ts';
import { startSim, type SimProcess } from './support/sim.ts';
import { recordCspViolations, type HudWindow } from './fixtures.ts';

interface TwoBrokers {
  first: MosquittoService;
  second: MosquittoService;
  web: StaticServer;
}

const test = base.extend<{ brokers: TwoBrokers }>({
  // eslint-disable-next-line no-empty-pattern
  brokers: async ({}, use) => {
    ensureHudBuilt();
    const first = await startMosquitto();
    const second = await startMosquitto();
    const web = await serveStatic(HUD_DIST);
    try {
      await use({ first, second, web });
    } finally {
      await web.close();
      await first.dispose();
      await second.dispose();
    }
  },
});

const servo0 = (page: import('@playwright/test').Page) =>
  page.evaluate(() => (window as unknown as HudWindow).__armtwin!.store.pwm[0]!);

test('the page moves to the second broker when the first dies, shows the arm moving, and comes back', async ({
  page,
  brokers,
}, testInfo) => {
  test.setTimeout(150_000);
  const { first, second, web } = brokers;
  const arm = `e2e-brokers-${process.pid}`;
  const sim: SimProcess = startSim(
    `${first.url},${second.url}`,
    arm,
    testInfo.outputPath('sim.log'),
  );
  try {
    const list = `${first.wsUrl},${second.wsUrl}`;
    await recordCspViolations(page);
    await page.goto(`${web.url}?broker=${encodeURIComponent(list)}&arm=${arm}&role=operator`);
    const inUse = page.getByTestId('broker-in-use');
    await expect(inUse).toContainText(`Broker 1 of 2: ${first.wsUrl}`, { timeout: 30_000 });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.', { timeout: 30_000 });

    // The first broker hangs (SIGSTOP): the operator clicks "Take control", then the e-stop;
    // neither is acknowledged. Then it dies. What reaches the arm's topics on the second broker:
    const watch = await mqtt.connectAsync(second.url, { reconnectPeriod: 0 });
    const onSecond: string[] = [];
    watch.on('message', (t, p) => onSecond.push(`${t.split('/')[2]} ${p.toString()}`));
    const ctl = [`arm/${arm}/claim/+`, `arm/${arm}/control`, `arm/${arm}/control/+`];
    await watch.subscribeAsync(ctl, { qos: 0 });
    const holder = page.getByTestId('control-holder');
    await expect(holder).toHaveText(`Nobody controls ${arm}.`, { timeout: 30_000 });
    process.kill(first.pid!, 'SIGSTOP');
    await page.getByRole('button', { name: 'Take control' }).click();
    await page.getByTestId('estop').click();
    await first.kill();
    await expect(inUse).toContainText(`Broker 2 of 2: ${second.wsUrl}`, { timeout: 30_000 });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.', { timeout: 30_000 });
    await expect(page.getByTestId('arm-online')).toHaveText('online');
    // The e-stop is sent again on the second broker; the take is not (docs/protocol.md § Several
    // brokers): mqtt.js re-sends in order, so a re-sent take would have come before the stop.
    await expect.poll(() => onSecond, { timeout: 20_000 }).toContain('control #255PDST!');
    expect(onSecond.filter((m) => m.startsWith('claim'))).toEqual([]);
    await expect(holder).toHaveText(`Nobody controls ${arm}.`, { timeout: 20_000 });
    await watch.endAsync();

    // The arm, on the second broker too, moves; the page shows it moving.
    const before = await servo0(page);
    const target = before < 1700 ? 2000 : 1300;
    const c = await mqtt.connectAsync(second.url, { reconnectPeriod: 0 });
    await c.publishAsync(`arm/${arm}/control`, `#000P${target}T1500!`, { qos: 1 });
    await c.endAsync();
    await expect
      .poll(async () => Math.abs((await servo0(page)) - before), { timeout: 20_000 })
      .toBeGreaterThan(100);

    await first.start();
    await expect(inUse).toContainText(`Broker 1 of 2: ${first.wsUrl}`, { timeout: 60_000 });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.', { timeout: 30_000 });
    await expect(page.getByTestId('arm-online')).toHaveText('online', { timeout: 30_000 });
    await testInfo.attach('back on broker 1', {
      body: await page.screenshot(),
      contentType: 'image/png',
    });
  } finally {
    await sim.stop();
    await testInfo
      .attach('sim.log', { path: sim.logFile, contentType: 'text/plain' })
      .catch(() => {});
  }
});
