/// <reference lib="dom" />
/**
 * The HUD end to end, state rates: at 5 Hz the twin moves between reports instead of jumping;
 * at 1 kHz the page keeps up and drops nothing. Real Mosquitto (WebSockets), the real simulator
 * (`armtwin sim --rate`), the built HUD in Debian Chromium; the twin's side through
 * `window.__armtwin`.
 */
import { pwmFromAngle } from '@armtwin/protocol';
import type { Page } from '@playwright/test';
import { expect, renderedAngles, shot, test, type HudWindow } from './fixtures.ts';
import { until } from './support/sim.ts';

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
