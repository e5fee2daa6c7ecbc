/// <reference lib="dom" />
/**
 * Teaching by showing, end to end: real Mosquitto, the real simulator, the real middleware
 * storing its poses in a real influxd, the built HUD in Chromium. The arm is jogged through three
 * moves with stops between them; once they are stored, the History panel's replay range becomes
 * a plan ("Make plan from this range"): the Plan panel holds a handful of waypoints (not one per
 * sample), the plan passes the checks and is previewed, and executing it takes the arm along the
 * recorded path: every pose the arm reports on the way is within the teaching tolerance of the
 * recorded path (poses compared with the path, not by time).
 */
import type { Page } from '@playwright/test';
import { pwmFromAngle, US_PER_DEG, PWM_CENTRE } from '@armtwin/protocol';
import { DEFAULT_TEACH_OPTIONS, tipPose } from '@armtwin/motion';
import { readRobotFolder } from '@armtwin/motion/robot-folder';
import { shot } from './fixtures.ts';
import { expect, historyGet, test } from './history-fixtures.ts';
import { until } from './support/sim.ts';

const robot = readRobotFolder('armtwin5').robot;
const TOL = DEFAULT_TEACH_OPTIONS;

/** The jogs: one joint at a time, each followed by a stop. */
const MOVES = [
  { slider: 'Elbow', index: 2, deg: 40 },
  { slider: 'Shoulder', index: 1, deg: 25 },
  { slider: 'Base', index: 0, deg: -35 },
];

interface TeachHook {
  __armtwin?: {
    history: {
      teach?: {
        samples: number;
        waypoints: number;
        error: { maxDeg: number; meanDeg: number; maxTipMm: number; meanTipMm: number };
      } | null;
    };
    robots: {
      waypoints: { list: { pwm?: number[] }[]; mode: string };
      runner: {
        state: string;
        progress: number;
        plan: { durationMs: number; targetTimes: number[] } | null;
      };
    };
  };
}

const teachProbe = (page: Page) =>
  page.evaluate(() => (window as unknown as TeachHook).__armtwin!.history.teach ?? null);

const taughtPoses = (page: Page) =>
  page.evaluate(() =>
    (window as unknown as TeachHook).__armtwin!.robots.waypoints.list.map((w) => w.pwm ?? null),
  );

/**
 * Distance from pose q to the nearest point of a polyline: worst servo (°), and tip (mm). Each
 * segment is tried at q's projection onto it (in pulses) and at ten points along it.
 */
function distanceToPath(q: readonly number[], path: readonly (readonly number[])[]) {
  let deg = Infinity;
  let mm = Infinity;
  const tq = tipPose(robot, q);
  const at = (p: readonly number[]) => {
    deg = Math.min(deg, Math.max(...p.map((v, i) => Math.abs(v - q[i]!) / US_PER_DEG)));
    const tp = tipPose(robot, p);
    mm = Math.min(mm, Math.hypot(tp.x - tq.x, tp.y - tq.y, tp.z - tq.z));
  };
  for (let k = 0; k + 1 < path.length; k++) {
    const a = path[k]!;
    const b = path[k + 1]!;
    const len2 = a.reduce((sum, v, i) => sum + (b[i]! - v) ** 2, 0);
    const dot = a.reduce((sum, v, i) => sum + (q[i]! - v) * (b[i]! - v), 0);
    const u = len2 > 0 ? Math.min(1, Math.max(0, dot / len2)) : 0;
    at(a.map((v, i) => v + (b[i]! - v) * u));
    for (let s = 0; s <= 10; s++) at(a.map((v, i) => v + ((b[i]! - v) * s) / 10));
  }
  return { deg, mm };
}

test('teach: a jogged motion becomes a plan of a few waypoints that retraces it', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  test.setTimeout(150_000);
  const { page } = hud;
  await page.waitForTimeout(1200); // a moment at the start, recorded still
  const initial = [...arm.observer.pwm];
  const initialSliders: string[] = [];
  for (const m of MOVES)
    initialSliders.push(
      await page.getByRole('slider', { name: m.slider, exact: true }).inputValue(),
    );
  for (const m of MOVES) {
    await page.getByRole('slider', { name: m.slider, exact: true }).fill(String(m.deg));
    const want = pwmFromAngle(m.deg, 1);
    await until(() => arm.observer.pwm[m.index] === want, 15_000, `the sim's ${m.slider}`);
    await page.waitForTimeout(1200); // a stop
  }
  const final = [...arm.observer.pwm];
  // Stored: the newest pose frame has the final pose.
  await expect
    .poll(
      async () => {
        const pose = await historyGet<{ ids: string[]; angles: (number | null)[][] }>(
          stack,
          'pose',
          { arm: arm.id, start: '-5m' },
        );
        const last = pose.angles.at(-1) ?? [];
        return MOVES.map((m) => last[pose.ids.indexOf(`00${m.index}`)] ?? null);
      },
      { timeout: 20_000 },
    )
    .toEqual(MOVES.map((m) => expect.closeTo((final[m.index]! - PWM_CENTRE) / US_PER_DEG, 6)));
  await page.waitForTimeout(1000); // a stop at the end, stored too

  // The recording the page will teach from: what the API serves for the panel's range.
  await page.locator('summary', { hasText: 'History' }).click();
  await page.getByRole('tab', { name: 'Replay' }).click();
  await page.getByRole('button', { name: 'Load replay' }).click();
  await expect(page.getByTestId('replay-angles')).toBeVisible();
  const recorded = await page.evaluate(() => {
    const rec = (
      window as unknown as {
        __armtwin: {
          replay: { record: { ids: string[]; times: number[]; angles: (number | null)[][] } };
        };
      }
    ).__armtwin.replay.record;
    return { ids: rec.ids, times: rec.times, angles: rec.angles };
  });
  const path = recorded.angles
    .filter((row) => row.slice(0, 6).every((a) => a !== null))
    .map((row) =>
      robot.ids.map((id) => PWM_CENTRE + row[recorded.ids.indexOf(`00${id}`)]! * US_PER_DEG),
    );

  await page.getByRole('button', { name: 'Make plan from this range' }).click();
  await expect(page.getByTestId('teach-note')).toContainText('Plan made:');
  const made = (await teachProbe(page))!;
  console.log(
    `teach e2e: ${made.samples} samples → ${made.waypoints} waypoints; reconstruction max ${made.error.maxDeg.toFixed(2)}° / ${made.error.maxTipMm.toFixed(2)} mm, mean ${made.error.meanDeg.toFixed(2)}° / ${made.error.meanTipMm.toFixed(2)} mm`,
  );
  // A handful of waypoints: the start and one per stop (a few more if a move was not straight).
  expect(made.waypoints).toBeGreaterThanOrEqual(MOVES.length + 1);
  expect(made.waypoints).toBeLessThanOrEqual(MOVES.length + 4);
  expect(made.samples).toBeGreaterThan(5 * made.waypoints); // not one per sample
  expect(made.error.maxDeg).toBeLessThanOrEqual(TOL.jointDeg);
  expect(made.error.maxTipMm).toBeLessThanOrEqual(TOL.tipMm);
  const rows = page.locator('.plan .waypoint');
  await expect(rows).toHaveCount(made.waypoints);
  // The last waypoint is where the arm ended.
  const poses = await taughtPoses(page);
  poses.at(-1)!.forEach((p, i) => expect(Math.abs(p! - final[i]!)).toBeLessThan(2 * US_PER_DEG));

  // Previewed on the ghost, in joint space at the recorded pace.
  await page.getByRole('button', { name: 'Preview', exact: true }).click();
  await expect(page.getByTestId('plan-note')).toContainText(
    'Planned: each axis (joint space) at the recorded pace',
  );
  await shot(page, testInfo, 'teach-plan-preview');

  // Jogged back to where the recording began, so the whole run is the taught motion.
  for (const [k, m] of [...MOVES.entries()].reverse()) {
    await page.getByRole('slider', { name: m.slider, exact: true }).fill(initialSliders[k]!);
    await until(() => arm.observer.pwm[m.index] === initial[m.index], 15_000, `${m.slider} back`);
  }
  // Executed: every pose the arm reports on the way (sampled every 20 ms) is compared with the
  // recorded path.
  const reported: { at: number; q: number[] }[] = [];
  const sampler = setInterval(
    () => reported.push({ at: Date.now(), q: [...arm.observer.pwm] }),
    20,
  );
  try {
    await page.getByRole('button', { name: 'Execute', exact: true }).click();
    for (const end = Date.now() + 60_000; Date.now() < end;) {
      const state = await page.evaluate(
        () => (window as unknown as TeachHook).__armtwin!.robots.runner.state,
      );
      if (state !== 'running' && state !== 'paused') break;
      await page.waitForTimeout(20); // the next look
    }
  } finally {
    clearInterval(sampler);
  }
  await expect(page.getByTestId('plan-run')).toHaveText(/^Done/);
  const trace = reported.map((r) => r.q);
  arm.observer.pwm.forEach((p, i) => expect(Math.abs(p - final[i]!)).toBeLessThan(2 * US_PER_DEG));
  let maxDeg = 0;
  let maxMm = 0;
  let sumDeg = 0;
  let sumMm = 0;
  let worst = 0;
  for (const [k, q] of trace.entries()) {
    const d = distanceToPath(q, path);
    if (d.mm > maxMm) worst = k;
    maxDeg = Math.max(maxDeg, d.deg);
    maxMm = Math.max(maxMm, d.mm);
    sumDeg += d.deg;
    sumMm += d.mm;
  }
  console.log(
    `teach e2e: executed ${trace.length} reported poses; distance to the recorded path max ${maxDeg.toFixed(2)}° / ${maxMm.toFixed(2)} mm, mean ${(sumDeg / trace.length).toFixed(2)}° / ${(sumMm / trace.length).toFixed(2)} mm (worst: pose ${worst}, ${JSON.stringify(trace[worst])})`,
  );
  expect(trace.length).toBeGreaterThan(20);
  expect(maxDeg).toBeLessThanOrEqual(TOL.jointDeg);
  expect(maxMm).toBeLessThanOrEqual(TOL.tipMm);
  await shot(page, testInfo, 'teach-plan-done');
});
