/// <reference lib="dom" />
/**
 * "Malformed flood", the HUD's part: 10,000 malformed frames per second for 10 s on
 * the arm's status topic (100 messages of 100 frames a second, from mqtt.js in this process)
 * while the simulator streams real state on the same topic. The page stays responsive (a jog
 * made mid-flood reaches the arm, the twin keeps following, data stays live), its JS heap stays
 * bounded, and every malformed frame is counted and shown in the Status panel.
 */
import mqtt from 'mqtt';
import { armTopics } from '@armtwin/protocol';
import { expect, shot, test } from './fixtures.ts';
import { until } from './support/sim.ts';

/** Five malformed frames, each dropped and counted once by the protocol reader. */
const UNIT = '#000P9999!#00AP1500!$XYZ:1!#001T999V99999!$KMS:a,b!';
const PAYLOAD = UNIT.repeat(20); // 100 frames
const MESSAGES_PER_S = 100;
const SECONDS = 10;
const SENT = MESSAGES_PER_S * SECONDS * 100;

interface FloodProbe {
  __armtwin: {
    store: { counters: { dropped: number; messages: number }; rendered: Float64Array };
  };
}

test('malformed flood: the page stays responsive, its heap bounded, and counts every bad frame', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  test.setTimeout(120_000);
  const { page } = hud;
  const cdp = await page.context().newCDPSession(page);
  const heap = async () => {
    await cdp.send('HeapProfiler.collectGarbage');
    const { usedSize } = await cdp.send('Runtime.getHeapUsage');
    return usedSize;
  };
  const dropped = () =>
    page.evaluate(() => (window as unknown as FloodProbe).__armtwin.store.counters.dropped);
  const droppedBefore = await dropped();
  const heapBefore = await heap();

  const flooder = await mqtt.connectAsync(stack.broker.url, { clientId: `flood-${arm.id}` });
  const topic = armTopics(arm.id).status;
  let sent = 0;
  const done = new Promise<void>((resolve) => {
    const timer = setInterval(() => {
      for (let i = 0; i < MESSAGES_PER_S / 10; i++) {
        if (sent >= MESSAGES_PER_S * SECONDS) break;
        flooder.publish(topic, PAYLOAD, { qos: 1 });
        sent++;
      }
      if (sent >= MESSAGES_PER_S * SECONDS) {
        clearInterval(timer);
        resolve();
      }
    }, 100);
  });
  try {
    // Mid-flood: the page answers, data is live, and a jog reaches the arm and the twin.
    await page.waitForTimeout(3000);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    const since = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('40');
    await until(
      () => arm.observer.commands(since).some((c) => /^#000P\d{4}T\d{4}!$/.test(c)),
      5000,
      'the jog on the control topic',
    );
    await until(() => Math.abs(arm.observer.pwm[0]! - 1796) < 10, 10_000, 'the arm at 40°');
    await expect
      .poll(() =>
        page.evaluate(() => (window as unknown as FloodProbe).__armtwin.store.rendered[0]),
      )
      .toBeCloseTo(40, 0); // degrees, as drawn
    await shot(page, testInfo, 'flood-mid');
    await done;
    await flooder.endAsync();

    // Every malformed frame counted, and shown.
    await expect.poll(dropped, { timeout: 15_000 }).toBe(droppedBefore + SENT);
    await expect(page.getByTestId('dropped')).toContainText(`${droppedBefore + SENT} frames`);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    const heapAfter = await heap();
    testInfo.annotations.push({
      type: 'JS heap before → after the flood',
      description: `${(heapBefore / 2 ** 20).toFixed(1)} → ${(heapAfter / 2 ** 20).toFixed(1)} MiB`,
    });
    // 5.1 MB of junk went through the page; keeping even the raw bytes would exceed this.
    expect(heapAfter - heapBefore).toBeLessThan(4 * 2 ** 20);
  } finally {
    await flooder.endAsync().catch(() => {});
  }
});
