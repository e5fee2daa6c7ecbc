/// <reference lib="dom" />
/**
 * The deadman on the production broker: an operator's page on Mosquitto 2.0 jogs the
 * simulated arm, then its connection stalls (a proxy stops forwarding: no FIN, no DISCONNECT,
 * what a frozen page or a pulled cable looks like). Mosquitto notices the dead connection only
 * seconds after 1.5 × keep-alive, so the arm must be stopped by the controller's lease on the
 * page's beat (docs/protocol.md "The operator's lease"): the `$ERR:deadman stop!` comes before
 * the broker publishes the will `0`. The time taken is reported, not asserted (see bench).
 */
import { armTopics } from '@armtwin/protocol';
import { expect, shot, test, type HudWindow } from './fixtures.ts';
import { startStallProxy } from './support/stall-proxy.ts';
import { until } from './support/sim.ts';

const KEEPALIVE_S = 2;

test('deadman on Mosquitto: a page that stalls mid-jog is let go by the lease, before the will', async ({
  page,
  stack,
  arm,
}, testInfo) => {
  test.setTimeout(90_000);
  const topics = armTopics(arm.id);
  await arm.observer.client.subscribeAsync(topics.operator, { qos: 1 });
  const proxy = await startStallProxy(stack.broker.wsPort);
  try {
    const broker = `ws://127.0.0.1:${proxy.port}`;
    await page.goto(
      `${stack.web.url}?broker=${encodeURIComponent(broker)}&arm=${arm.id}&role=operator&jogms=9000&keepalive=${KEEPALIVE_S}`,
    );
    await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    const operator = (since = 0) =>
      arm.observer.messages.filter((m) => m.topic === topics.operator && m.at >= since);
    // The page holds the arm and beats: several retained 1s.
    await until(() => operator().filter((m) => m.text === '1').length >= 4, 10_000, 'beats');

    const start = arm.observer.pwm[0]!;
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('120');
    await until(() => Math.abs(arm.observer.pwm[0]! - start) > 60, 10_000, 'the base to move');

    const stalledAt = Date.now();
    proxy.stall();
    const stop = await until(
      () =>
        arm.observer.messages.find(
          (m) =>
            m.topic === topics.status && m.at >= stalledAt && m.text.includes('$ERR:deadman stop!'),
        ),
      20_000,
      '$ERR:deadman stop!',
    );
    const willBeforeStop = operator(stalledAt).filter((m) => m.at <= stop.at && m.text === '0');
    expect(willBeforeStop, 'the stop came from the lease, not from the will').toEqual([]);
    testInfo.annotations.push({
      type: 'deadman stop after (Mosquitto, lease)',
      description: `${stop.at - stalledAt} ms`,
    });

    // Stopped where it was, far from the target: positions no longer change.
    await new Promise((r) => setTimeout(r, 500));
    const held = arm.observer.pwm[0]!;
    await new Promise((r) => setTimeout(r, 1500));
    expect(arm.observer.pwm[0]).toBe(held);
    expect(Math.abs(held - start)).toBeGreaterThan(60);
    const target = Number(
      arm.observer
        .control()
        .flatMap((t) => [...t.matchAll(/#000P(\d+)T/g)].map((m) => m[1]))
        .at(-1),
    );
    expect(Math.abs(held - target), 'stopped on the way, not at the jog target').toBeGreaterThan(
      50,
    );

    // Mosquitto still publishes the will in the end: the topic says nobody holds the arm.
    const will = await until(
      () => operator(stalledAt).find((m) => m.text === '0'),
      20_000,
      'the will: operator = 0',
    );
    testInfo.annotations.push({
      type: 'Mosquitto will after',
      description: `${will.at - stalledAt} ms`,
    });
    await shot(page, testInfo, 'deadman-mosquitto');
  } finally {
    await page.close();
    await proxy.close();
  }
});
