/// <reference lib="dom" />
/**
 * The HUD end to end: real Mosquitto (WebSockets), the real simulator (`armtwin sim`), the built
 * HUD in Debian Chromium. The simulator's side is observed with an mqtt.js subscriber; the
 * twin's side through the page and its read-only debug hook `window.__armtwin`.
 */
import { angleFromPwm, pwmFromAngle } from '@armtwin/protocol';
import type { Page } from '@playwright/test';
import {
  DEMO_ARM,
  forwardKinematics,
  jointsFromServoAngles,
  solveIk,
  type Quad,
} from '@armtwin/ik';
import { expect, renderedAngles, shot, test, type HudWindow } from './fixtures.ts';
import { until } from './support/sim.ts';

/** Luminance spread and coarse colour count of a PNG, decoded by the browser. */
async function pixelStats(page: Page, png: Buffer) {
  return page.evaluate(async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = document.createElement('canvas');
    c.width = img.width;
    c.height = img.height;
    const ctx = c.getContext('2d')!;
    ctx.drawImage(img, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let sum = 0;
    let sum2 = 0;
    let n = 0;
    let warm = 0; // the arm's orange and amber parts: nothing else in the scene is that colour
    const colours = new Set<number>();
    for (let i = 0; i < d.length; i += 4) {
      const [r, g, b] = [d[i]!, d[i + 1]!, d[i + 2]!];
      const l = 0.2126 * r + 0.7152 * g + 0.0722 * b;
      sum += l;
      sum2 += l * l;
      n++;
      colours.add(((r >> 3) << 10) | ((g >> 3) << 5) | (b >> 3));
      if (r > 150 && r - b > 90 && g > 60) warm++;
    }
    const mean = sum / n;
    return { std: Math.sqrt(sum2 / n - mean * mean), colours: colours.size, warm };
  }, png.toString('base64'));
}

test('model: the arm renders, the canvas is not blank', async ({ hud }, testInfo) => {
  const { page } = hud;
  await expect(page.locator('#message')).toBeHidden();
  // A render worker's first frame (at the view's size) comes a moment after the page is ready.
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as HudWindow).__armtwin!.viewer.renderedFrames),
    )
    .toBeGreaterThan(0);
  const png = await page.locator('#view canvas').screenshot();
  const stats = await pixelStats(page, png);
  testInfo.annotations.push({ type: 'pixels', description: JSON.stringify(stats) });
  expect(stats.std).toBeGreaterThan(8);
  expect(stats.colours).toBeGreaterThan(100);
  expect(stats.warm).toBeGreaterThan(1000);
  await shot(page, testInfo, 'model');
});

test('model: a mesh that fails to load is named on the page, and the rest of the arm is drawn', async ({
  page,
  stack,
}, testInfo) => {
  await page.route('**/meshes/forearm.stl', (route) =>
    route.fulfill({ status: 404, body: 'gone' }),
  );
  await page.goto(`${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=nobody`);
  const note = page.getByTestId('mesh-failures');
  await expect(note).toContainText('1 mesh failed to load');
  await expect(note).toContainText('forearm.stl');
  await page.waitForFunction(() => (window as unknown as HudWindow).__armtwin?.ready === true);
  await expect(page.getByRole('button', { name: 'Emergency stop' })).toBeVisible();
  await shot(page, testInfo, 'mesh-error');
});

test('model: a robot description that fails to load shows an error, not a blank page', async ({
  page,
  stack,
}, testInfo) => {
  await page.route('**/armtwin5.urdf', (route) => route.fulfill({ status: 404, body: 'gone' }));
  await page.goto(`${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=nobody`);
  await expect(page.getByRole('alert')).toContainText('The arm model failed to load');
  await expect(page.getByRole('alert')).toContainText('armtwin5.urdf');
  await expect(page.getByRole('button', { name: 'Emergency stop' })).toBeVisible();
  await shot(page, testInfo, 'model-error');
});

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

test('floor: a target or jog below the floor is refused in the page, with the reason', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const since = Date.now();
  // Command box: reachable by the IK, but the hand would end 11 mm under the floor.
  const box = page.getByRole('textbox', { name: 'Command' });
  await box.fill('move to 200 0 -50');
  await page.getByRole('button', { name: 'Send', exact: true }).click();
  await expect(page.getByTestId('command-error')).toHaveText(
    /^Not sent: tip \d+\.\d mm below the floor \(z -\d+\.\d < 0\)\.$/,
  );
  await expect(page.getByTestId('command-entry')).toHaveCount(0);
  // Cartesian panel: the preview says so, and Move sends nothing.
  await page.getByLabel('X', { exact: true }).fill('200');
  await page.getByLabel('Y', { exact: true }).fill('0');
  await page.getByLabel('Z', { exact: true }).fill('-50');
  await expect(page.getByTestId('ik-preview')).toHaveText(
    /^Unreachable: tip \d+\.\d mm below the floor \(z -\d+\.\d < 0\) \(code 24\)\.$/,
  );
  await page.getByRole('button', { name: 'Move' }).click();
  await expect(page.getByTestId('kms-refusal')).toContainText('below the floor');
  // Jog: upper arm level is fine (hand at z 100); the forearm down from there is not.
  await page.getByRole('slider', { name: 'Shoulder', exact: true }).fill('-90');
  const level = pwmFromAngle(-90, 1);
  await until(() => arm.observer.pwm[1] === level, 10_000, `the sim's shoulder at ${level} µs`);
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('-90');
  await expect(page.getByTestId('jog-refusal')).toHaveText(
    /^Not sent: tip \d+\.\d mm below the floor/,
  );
  await page.waitForTimeout(1000);
  expect(arm.observer.pwm[2]).toBe(1500);
  expect(arm.observer.commands(since)).toEqual([`#001P${String(level).padStart(4, '0')}T0100!`]);
  await shot(page, testInfo, 'floor-refused');
});

test('cartesian: the target starts at the tip of the arm, which it reaches', async ({ hud }) => {
  const { page } = hud;
  // armtwin5 at home points straight up: its tip is at (0, 0, 453).
  await expect(page.getByLabel('X', { exact: true })).toHaveValue('0');
  await expect(page.getByLabel('Y', { exact: true })).toHaveValue('0');
  await expect(page.getByLabel('Z', { exact: true })).toHaveValue('453');
  // Retyped as it stands (a value put back unchanged is not an edit), the target is reachable.
  await page.getByLabel('Z', { exact: true }).fill('');
  await page.getByLabel('Z', { exact: true }).fill('453');
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
});

test('cartesian: an unreachable target shows the reason and publishes nothing', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  const before = [...arm.observer.pwm];
  const since = Date.now();
  await page.getByLabel('X', { exact: true }).fill('600');
  await page.getByLabel('Y', { exact: true }).fill('0');
  await page.getByLabel('Z', { exact: true }).fill('100');
  await expect(page.getByTestId('ik-preview')).toHaveText('Unreachable: out of reach (code 2).');
  await page.getByRole('button', { name: 'Move' }).click();
  await expect(page.getByTestId('kms-refusal')).toHaveText('Not sent: out of reach (code 2).');
  await page.keyboard.press('Enter'); // submitting the form again does not send either
  await page.waitForTimeout(1500);
  // Only the HUD's $PNG round-trip pings may appear on the control topic.
  expect(arm.observer.commands(since)).toEqual([]);
  expect(arm.observer.pwm).toEqual(before);
  await shot(page, testInfo, 'unreachable');
});

test('cartesian: a reachable target reaches the arm', async ({ hud, arm }, testInfo) => {
  const { page } = hud;
  const [x, y, z] = [180, 100, 80];
  const ik = solveIk(x, y, z);
  expect(ik.code).toBe(0);
  const since = Date.now();
  await page.getByLabel('X', { exact: true }).fill(String(x));
  await page.getByLabel('Y', { exact: true }).fill(String(y));
  await page.getByLabel('Z', { exact: true }).fill(String(z));
  await expect(page.getByTestId('ik-preview')).toContainText('Reachable');
  await expect(page.getByTestId('ghost-shows')).toContainText('previewed target pose');
  await shot(page, testInfo, 'reachable-preview');
  await page.getByRole('button', { name: 'Move' }).click();
  await until(
    () => arm.observer.commands(since).includes(`$KMS:${x},${y},${z},1500!`),
    5000,
    'the $KMS command',
  );
  await expect(page.getByTestId('kms-reply')).toContainText('code 0 — accepted, moving');
  await until(
    () => ik.pwm.every((p, i) => Math.abs((arm.observer.pwm[i] ?? 0) - p) <= 1),
    10_000,
    `the sim at ${ik.pwm.join(', ')} µs`,
  );
  const s = arm.observer.pwm.slice(0, 4).map((p) => angleFromPwm(p, 1)) as Quad;
  const tip = forwardKinematics(jointsFromServoAngles(s));
  expect(Math.hypot(tip.x - x, tip.y - y, tip.z - z)).toBeLessThan(2);
  await expect
    .poll(
      async () => {
        const r = await renderedAngles(page);
        return Math.max(...ik.servoAngles.map((a, i) => Math.abs(r[i]! - a)));
      },
      { timeout: 5000 },
    )
    .toBeLessThan(0.5);
  await shot(page, testInfo, 'reachable-arrived');
});

test('health: an injected overheat turns that servo critical', async ({ hud, arm }, testInfo) => {
  const { page } = hud;
  await expect(page.getByTestId('health-2')).toHaveClass(/temp-normal/);
  await arm.observer.fault({ fault: 'overheat', id: 2, celsius: 150 });
  await expect(page.getByTestId('health-2')).toHaveClass(/temp-critical/, { timeout: 30_000 });
  await expect(page.getByRole('alert').filter({ hasText: 'Overheating' })).toContainText('Elbow');
  await expect(page.getByRole('alert').filter({ hasText: 'Overheating' })).toContainText(
    'Cut the power',
  );
  await expect(page.getByTestId('health-announcer')).toContainText('Elbow: temperature');
  await expect(page.getByTestId('health-announcer')).toContainText(
    'critical, overheating — cut the power',
  );
  await expect(page.getByTestId('health-1')).not.toHaveClass(/temp-critical/);
  await shot(page, testInfo, 'overheat');
});

test.describe('emergency stop', () => {
  // Slow jog moves (6 s), so the arm is still moving when the stop comes.
  test.use({ hudQuery: '&jogms=6000' });

  test('the button and Escape publish #255PDST! at QoS 1 and halt the simulator', async ({
    hud,
    arm,
  }, testInfo) => {
    const { page } = hud;
    const target = pwmFromAngle(120, 1);
    const jogAt = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).fill('120');
    await until(() => (arm.observer.pwm[0] ?? 0) > 1560, 10_000, 'the base to start moving');
    const since = Date.now();
    await page.getByRole('button', { name: 'Emergency stop' }).click();
    await until(
      () => arm.observer.control(since).includes('#255PDST!'),
      5000,
      '#255PDST! on the control topic',
    );
    expect(arm.observer.controlMessages(since).find((m) => m.text === '#255PDST!')?.qos).toBe(1);
    // Judged once the 6 s jog would have ended, so a late status report cannot pass for a stop:
    // an arm that was not stopped is at the target by then; a stopped one stands still, short.
    await page.waitForTimeout(Math.max(0, jogAt + 6500 - Date.now()));
    const stoppedAt = arm.observer.pwm[0]!;
    await page.waitForTimeout(1000);
    expect(Math.abs(arm.observer.pwm[0]! - stoppedAt)).toBeLessThanOrEqual(1);
    expect(arm.observer.pwm[0]!).toBeLessThan(target - 50);
    await shot(page, testInfo, 'estop');

    const again = Date.now();
    await page.getByRole('slider', { name: 'Base', exact: true }).focus();
    await page.keyboard.press('Escape');
    await until(
      () => arm.observer.control(again).includes('#255PDST!'),
      5000,
      '#255PDST! after Escape',
    );
  });
});

test('offline: killing the simulator shows "offline" and disables jogging', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  await expect(page.getByTestId('arm-online')).toHaveText('online');
  await arm.sim.kill();
  await expect(page.getByTestId('arm-online')).toHaveText('offline', { timeout: 15_000 });
  await expect(page.getByTestId('freshness')).toContainText('Data is stale');
  await expect(page.getByRole('slider', { name: 'Base', exact: true })).toBeDisabled();
  await shot(page, testInfo, 'offline');
});

/** Samples the twin's drawn angle of servo `id` and the time on every animation frame for `ms`. */
function sampleFrames(page: Page, id: number, ms: number) {
  return page.evaluate(
    ([id, ms]) =>
      new Promise<{ t: number; v: number }[]>((resolve) => {
        const out: { t: number; v: number }[] = [];
        const end = performance.now() + ms;
        const step = (t: number) => {
          out.push({ t, v: (window as unknown as HudWindow).__armtwin!.store.rendered[id]! });
          if (t < end) requestAnimationFrame(step);
          else resolve(out);
        };
        requestAnimationFrame(step);
      }),
    [id, ms] as const,
  );
}

test.describe('interpolation at 5 Hz', () => {
  test.use({ simArgs: ['--rate', '5'], hudQuery: '&jogms=4000' });

  test('the twin moves between the 5 Hz reports instead of jumping', async ({
    hud,
    arm,
  }, testInfo) => {
    const { page } = hud;
    await page.getByRole('slider', { name: 'Elbow', exact: true }).fill('80');
    await until(() => (arm.observer.pwm[2] ?? 1500) > 1560, 10_000, 'the elbow to start moving');
    const frames = await sampleFrames(page, 2, 1500);
    const speeds: number[] = [];
    let still = 0;
    for (let i = 1; i < frames.length; i++) {
      const dv = frames[i]!.v - frames[i - 1]!.v;
      const dt = frames[i]!.t - frames[i - 1]!.t;
      if (dt <= 0) continue;
      if (Math.abs(dv) < 1e-6) still++;
      speeds.push(dv / (dt / 1000));
    }
    const first = frames[0]!;
    const last = frames.at(-1)!;
    const mean = (last.v - first.v) / ((last.t - first.t) / 1000);
    testInfo.annotations.push({
      type: 'frames',
      description: `${frames.length} frames, mean ${mean.toFixed(1)}°/s, max ${Math.max(...speeds).toFixed(1)}°/s, still ${still}`,
    });
    // 20°/s reported every 200 ms. Drawn as reported, most frames would stand still and the
    // others would jump 4° at once (about 12× the mean speed, measured with interpolation
    // switched off). Interpolated, nearly every frame moves, at about the mean speed. The
    // bound on the fastest frame leaves room for a loaded machine's uneven frame times.
    expect(mean).toBeGreaterThan(5);
    expect(still / speeds.length).toBeLessThan(0.3);
    expect(Math.max(...speeds)).toBeLessThan(4 * mean);
  });
});

test.describe('1 kHz state rate', () => {
  test.use({ simArgs: ['--rate', '1000'] });

  test('the page keeps up: the twin follows, the rate shows, nothing is dropped', async ({
    hud,
    arm,
  }, testInfo) => {
    const { page } = hud;
    await page.getByRole('slider', { name: 'Shoulder', exact: true }).fill('-30');
    const want = pwmFromAngle(-30, 1);
    await until(() => arm.observer.pwm[1] === want, 10_000, `the sim's shoulder at ${want} µs`);
    await expect
      .poll(async () => Math.abs((await renderedAngles(page))[1]! + 30), { timeout: 3000 })
      .toBeLessThan(0.5);
    await expect
      .poll(
        async () =>
          Number(
            (await page.getByText(/state [\d.]+\/s/).textContent())?.match(/state ([\d.]+)/)?.[1],
          ),
        {
          timeout: 5000,
        },
      )
      .toBeGreaterThan(500);
    await expect(page.getByTestId('dropped')).toHaveText('0 frames');
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    await shot(page, testInfo, 'rate-1khz');
  });
});
