/// <reference lib="dom" />
/**
 * Replay of a robot that is not the 5-axis demo arm, end to end: a real `armtwin sim --profile
 * track6` (7 axes, a prismatic track, mixed polarities and offsets) on Mosquitto, the middleware
 * storing it in a real influxd, the built HUD in Chromium on that arm. What track6 did must come
 * back on the replay's sibling: the three.js track6 model's own joints (read by their URDF
 * names from the profile, metres for the track, radians for the rest), while the live arm stays
 * where the arm is.
 */
import type { Page } from '@playwright/test';
import { angleFromPwm } from '@armtwin/protocol';
import { jointFromPwm, pwmFromServo } from '@armtwin/robot';
import { shot } from './fixtures.ts';
import { expect, historyGet, test } from './history-fixtures.ts';
import { until } from './support/sim.ts';
import { loadProfile, startProfiledArm } from './support/profiled-arm.ts';

const TRACK6 = loadProfile('track6');
const servo = (i: number) => TRACK6.servos[i]!;
const wireId = (i: number) => String(servo(i).id).padStart(3, '0');

/** The moves: the track to 1500 mm, A2 (polarity −1) to 30°, A3 (offset 15°) to 60°. */
const MOVES = [
  { index: 0, slider: 'Track', value: 1500 },
  { index: 2, slider: 'A2 upper arm', value: 30 },
  { index: 3, slider: 'A3 forearm', value: 60 },
].map((m) => {
  const s = servo(m.index);
  return { ...m, pwm: pwmFromServo(s, s.type === 'revolute' ? m.value - s.offset : m.value) };
});

interface Track6Hook {
  __armtwin?: {
    ready: boolean;
    joints(which?: 'robot' | 'ghost' | 'sibling'): number[];
    robots: { active: { spec: { name: string }; source: string } };
    replay: { record: object | null };
    viewer: { drawnWorld: { getObjectByName(n: string): unknown } };
  };
}

/** The sibling's URDF joint values by joint name (null while hidden), and where it stands. */
const sibling = (page: Page, names: string[]) =>
  page.evaluate((ns) => {
    const robot = (window as unknown as Track6Hook).__armtwin!.viewer.drawnWorld.getObjectByName(
      'replay sibling',
    ) as
      | {
          visible: boolean;
          position: { x: number };
          joints: Record<string, { angle: number }>;
        }
      | undefined;
    if (!robot?.visible) return null;
    return { x: robot.position.x, values: ns.map((n) => robot.joints[n]!.angle) };
  }, names);

const liveJoints = (page: Page) =>
  page.evaluate(() => (window as unknown as Track6Hook).__armtwin!.joints());

test('replay on track6: the sibling track6 model takes the recorded poses', async ({
  page,
  stack,
}, testInfo) => {
  test.setTimeout(120_000);
  const id = `e2e-t6-replay-${process.pid}`;
  const arm = await startProfiledArm(
    stack.broker.url,
    id,
    TRACK6,
    testInfo.outputPath('sim-track6.log'),
  );
  try {
    page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
    await page.goto(
      `${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=${id}&role=operator&render=main`, // the sibling's object lives on the page only then
    );
    await page.waitForFunction(
      () => (window as unknown as Track6Hook).__armtwin?.ready === true,
      null,
      { timeout: 30_000 },
    );
    await expect
      .poll(
        () =>
          page.evaluate(() => {
            const a = (window as unknown as Track6Hook).__armtwin!.robots.active;
            return { name: a.spec.name, source: a.source };
          }),
        { timeout: 15_000 },
      )
      .toEqual({ name: 'track6', source: 'announced' });
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');

    const home = [...arm.observer.pwm];
    await page.waitForTimeout(1500); // a moment recorded at home
    const before = Date.now();
    for (const m of MOVES) {
      const slider = page.getByRole('slider', { name: m.slider, exact: true });
      await expect(slider).toBeEnabled();
      await slider.fill(String(m.value));
    }
    for (const m of MOVES)
      await until(
        () => arm.observer.pwm[m.index] === m.pwm,
        20_000,
        `the sim's ${m.slider} at ${m.pwm} µs`,
      );
    // Stored: the newest pose frame holds the final pulses' angles (§2 at k = 1).
    await expect
      .poll(
        async () => {
          const pose = await historyGet<{ ids: string[]; angles: (number | null)[][] }>(
            stack,
            'pose',
            { arm: id, start: '-5m' },
          );
          const last = pose.angles.at(-1) ?? [];
          return MOVES.map((m) => last[pose.ids.indexOf(wireId(m.index))] ?? null);
        },
        { timeout: 20_000 },
      )
      .toEqual(MOVES.map((m) => angleFromPwm(m.pwm, 1)));

    await page.locator('summary', { hasText: 'History' }).click();
    await page.getByRole('tab', { name: 'Replay' }).click();
    await page.getByRole('button', { name: 'Load replay' }).click();
    await expect(page.getByTestId('replay-angles')).toBeVisible();
    const names = TRACK6.servos.map((s) => s.joint);
    const scrubber = page.getByRole('slider', { name: 'Replay position' });

    // Before the moves: the sibling stands at home, clear of the live arm (behind its rail),
    // while the live arm stays where the arm is.
    await scrubber.fill(String(before - 1000));
    const atHome = TRACK6.servos.map((s, i) => jointFromPwm(s, home[i]!));
    await expect
      .poll(async () => (await sibling(page, names))?.values.map((v, i) => v - atHome[i]!))
      .toEqual(atHome.map(() => expect.closeTo(0, 4)));
    expect((await sibling(page, names))!.x).toBeLessThan(-4);
    const live = await liveJoints(page);
    for (const m of MOVES)
      expect(live[m.index]).toBeCloseTo(jointFromPwm(servo(m.index), m.pwm), 3);
    await shot(page, testInfo, 'track6-replay-before-moves');

    // Play at 8×: the track runs to 1.5 m, A2 and A3 to 30° and 60°, on the model itself.
    await page.getByLabel('Replay speed').selectOption('8');
    await page.getByRole('button', { name: 'Play', exact: true }).click();
    const moved = () =>
      sibling(
        page,
        MOVES.map((m) => names[m.index]!),
      );
    await expect
      .poll(async () => (await moved())?.values, { timeout: 15_000 })
      .toEqual(MOVES.map((m) => expect.closeTo(jointFromPwm(servo(m.index), m.pwm), 4)));
    // …which is what the sliders asked for, to the whole microsecond the wire carries.
    expect((await moved())!.values[0]).toBeCloseTo(1.5, 4);
    expect((await moved())!.values[1]).toBeCloseTo((30 * Math.PI) / 180, 2);
    expect((await moved())!.values[2]).toBeCloseTo((60 * Math.PI) / 180, 2);
    await expect(page.getByRole('button', { name: 'Play', exact: true })).toBeVisible();
    // The panel says it in the joints' own units: millimetres for the track.
    await expect(page.getByTestId('replay-angles')).toContainText(
      'Track 1500.0 mm · A1 column 0.0° · A2 upper arm 30.0° · A3 forearm 60.0°',
    );
    await shot(page, testInfo, 'track6-replay-after-moves');

    // Scrubbing back moves it back; Close hides it.
    await scrubber.fill(String(before - 500));
    await expect
      .poll(async () => (await moved())?.values[0])
      .toBeCloseTo(jointFromPwm(servo(0), home[0]!), 4);
    await page.getByRole('button', { name: 'Close', exact: true }).click();
    await expect.poll(() => sibling(page, names)).toBeNull();
  } finally {
    await arm.stop();
  }
});
