/// <reference lib="dom" />
/**
 * Several brokers in the page (docs/protocol.md § Several brokers): the HUD is given two
 * WebSocket brokers (two real Mosquittos) and `armtwin sim` the same two. The Status panel says
 * "Broker 1 of 2"; the first broker is killed: the page says "Broker 2 of 2", its data is live
 * again and a move sent on the second broker shows on the page's arm; the first comes back: the
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

    await first.kill();
    await expect(inUse).toContainText(`Broker 2 of 2: ${second.wsUrl}`, { timeout: 30_000 });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.', { timeout: 30_000 });
    await expect(page.getByTestId('arm-online')).toHaveText('online');

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
