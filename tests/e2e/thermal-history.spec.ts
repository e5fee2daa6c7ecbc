/// <reference lib="dom" />
/**
 * The thermal model in the History panel (issue 20 item 2), on the real stack of
 * ./history-fixtures.ts (Mosquitto, the simulator, the middleware with InfluxDB, the built HUD):
 * a servo stalls; the middleware's thermal watch warns of it and stores the warning; History
 * then draws the model's predicted temperature (dashed) beside the measured one, marks the
 * warning on the temperature chart, charts the motion's power, and lists the warning in the
 * control log, so an operator looking back sees when the model warned.
 */
import type { Page } from '@playwright/test';
import { encodeMove } from '@armtwin/protocol';
import { shot } from './fixtures.ts';
import { expect, historyGet, test } from './history-fixtures.ts';

interface ChartProbe {
  labels: string[];
  points: number[];
  markers: string[];
}
interface HistoryHook {
  __armtwin?: { history: { charts: Record<string, ChartProbe | undefined> } };
}

const chart = (page: Page, name: string) =>
  page.evaluate(
    (n) => (window as unknown as HistoryHook).__armtwin!.history.charts[n] ?? null,
    name,
  );

test('history: the predicted temperature beside the measured, and the stored early warning', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  // The shoulder jams and is asked to move: it pushes against the jam and heats, not moving.
  await arm.observer.fault({ fault: 'stall', id: 1 });
  await arm.observer.client.publishAsync(`arm/${arm.id}/control`, encodeMove(1, 1300, 1000), {
    qos: 1,
  });
  await expect
    .poll(
      async () =>
        (
          await historyGet<{ events: { kind: string; detail: string }[] }>(stack, 'audit', {
            arm: arm.id,
            start: '-5m',
          })
        ).events
          .filter((e) => e.kind === 'thermal-warning')
          .map((e) => e.detail.slice(0, 15)),
      { timeout: 30_000 },
    )
    .toEqual(['servo 001 heats']);
  await arm.observer.fault({ fault: 'clear' });

  await page.locator('summary', { hasText: 'History' }).click();
  await expect.poll(() => chart(page, 'temp'), { timeout: 15_000 }).not.toBeNull();
  const temp = (await chart(page, 'temp'))!;
  const shoulder = temp.labels.indexOf('predicted Shoulder');
  expect(shoulder).toBeGreaterThan(temp.labels.indexOf('Shoulder'));
  expect(temp.points[shoulder]).toBeGreaterThan(0);
  expect(temp.markers).toEqual(['⚠ Shoulder']);
  expect((await chart(page, 'volt'))!.labels).toContain('predicted Shoulder');
  const power = (await chart(page, 'power'))!;
  expect(power.labels).toEqual(['measured', 'predicted']);
  expect(Math.min(...power.points)).toBeGreaterThan(0);
  await expect(page.getByTestId('thermal-model-note')).toContainText('Dashed: the thermal model');
  await page.getByTestId('history-chart-temp').scrollIntoViewIfNeeded();
  await shot(page, testInfo, 'history-thermal');

  await page.getByRole('tab', { name: 'Tracking, alarms & control' }).click();
  const row = page.getByTestId('control-log').locator('tr', { hasText: 'servo 001 heats' });
  await expect(row).toContainText('thermal model');
  await expect(row).toContainText('faster than its model allows');
});
