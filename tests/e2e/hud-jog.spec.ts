/// <reference lib="dom" />
/**
 * The HUD end to end, jogging: a slider moves the simulator and the twin follows (from the
 * keyboard too), and a focused slider follows the arm. Real Mosquitto (WebSockets), the real
 * simulator (`armtwin sim`, observed with an mqtt.js subscriber), the built HUD in Debian Chromium.
 */
import { pwmFromAngle } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';
import { expect, renderedAngles, shot, test } from './fixtures.ts';
import { until } from './support/sim.ts';

test('jog: a slider moves the simulator and the twin follows; sliders work from the keyboard', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  for (const spec of DEMO_ARM.servos)
    await expect(page.getByRole('slider', { name: spec.name, exact: true })).toBeEnabled();

  const since = Date.now();
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('45');
  const elbow = pwmFromAngle(45, 1);
  await until(() => arm.observer.pwm[2] === elbow, 10_000, `the sim's elbow at ${elbow} µs`);
  expect(arm.observer.commands(since)).toContain(`#002P${elbow}T0100!`);
  await expect
    .poll(async () => Math.abs((await renderedAngles(page))[2]! - 45), { timeout: 5000 })
    .toBeLessThan(0.5);

  // Keyboard: five steps of 1° on the wrist roll.
  await page.getByRole('slider', { name: 'Wrist roll', exact: true }).focus();
  for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
  const roll = pwmFromAngle(5, 1);
  await until(() => arm.observer.pwm[4] === roll, 10_000, `the sim's wrist roll at ${roll} µs`);
  await expect
    .poll(async () => Math.abs((await renderedAngles(page))[4]! - 5), { timeout: 5000 })
    .toBeLessThan(0.5);
  // every move went out within the servo's limits
  for (const text of arm.observer.commands(since)) {
    const m = /^#(\d{3})P(\d{4})T\d{4}!$/.exec(text);
    expect(m, text).not.toBeNull();
  }
  await shot(page, testInfo, 'jog');
});

test('jog: a focused slider follows the arm when something else moves its joint', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const elbow = page.getByRole('slider', { name: 'Elbow', exact: true });
  await elbow.focus();
  for (let i = 0; i < 5; i++) await page.keyboard.press('ArrowRight');
  const five = pwmFromAngle(5, 1);
  await until(() => arm.observer.pwm[2] === five, 10_000, `the sim's elbow at ${five} µs`);
  await expect(elbow).toHaveValue('5');
  // Another operator (or a command, or a plan) moves the elbow back; the slider keeps focus.
  await arm.observer.client.publishAsync(`arm/${arm.id}/control`, '#002P1500T0200!', { qos: 1 });
  await until(() => arm.observer.pwm[2] === 1500, 10_000, "the sim's elbow back at 1500 µs");
  await expect(elbow).toBeFocused();
  await expect(elbow).toHaveValue('0');
  await shot(page, testInfo, 'jog-follows');
});
