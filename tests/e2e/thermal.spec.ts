/**
 * The thermal model's early warning in the HUD (issue 20 item 2), against the real simulator:
 * the Health panel says which model it uses (generic here: the e2e stack has no middleware to
 * fit one from), and a servo stalled against a jam is warned of in words, in orange, while its
 * reported temperature is still below the 60 °C alarm.
 */
import mqtt from 'mqtt';
import { encodeMove } from '@armtwin/protocol';
import { expect, shot, test } from './fixtures.ts';

test('health: a stalled servo is warned of before it reaches 60 °C', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  await expect(page.getByTestId('thermal-model')).toContainText('Thermal model: generic');
  await expect(page.getByTestId('health-1')).toHaveClass(/temp-normal/);
  await expect(page.getByTestId('thermal-warning')).toHaveCount(0);

  // The shoulder jams, then is asked to move: it pushes against the jam and heats, not moving.
  await arm.observer.fault({ fault: 'stall', id: 1 });
  const client = await mqtt.connectAsync(stack.broker.url);
  try {
    await client.publishAsync(`arm/${arm.id}/control`, encodeMove(1, 1300, 1000), { qos: 1 });
  } finally {
    await client.endAsync();
  }
  const warning = page.getByTestId('thermal-warning');
  await expect(warning).toContainText('Shoulder is heating', { timeout: 15_000 });
  await expect(warning).toContainText('more than its motion explains');
  // Warned first: the §5 alarm (60 °C) is still to come.
  await expect(page.getByTestId('health-1')).toHaveClass(/temp-normal/);
  await expect(page.getByTestId('health-1')).toHaveClass(/heating/);
  await expect(page.getByTestId('health-announcer')).toContainText('Shoulder is heating');
  await warning.scrollIntoViewIfNeeded();
  await shot(page, testInfo, 'thermal-early-warning');
  await expect(page.getByTestId('health-1')).toHaveClass(/temp-warning/, { timeout: 30_000 });
  await expect(page.getByTestId('health-0')).not.toHaveClass(/heating/);
});
