/// <reference lib="dom" />
/**
 * The History panel and replay end to end: real Mosquitto, the real simulator, the real
 * middleware writing to a real influxd, the built HUD in Chromium with `/api` on its own
 * origin (./history-fixtures.ts). What the simulator does now must show up in the panel: the
 * charts (read through `window.__armtwin.history`, what each uPlot chart was given), the
 * tracking table, the alarm log, a CSV download — and the replay's sibling arm must take the
 * recorded pose (`window.__armtwin.replay.angles`, and the three.js joint itself).
 */
import { execFileSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { angleFromPwm, encodeGroup, encodeHealth, pwmFromAngle } from '@armtwin/protocol';
import { DEMO_ARM } from '@armtwin/ik';
import { shot } from './fixtures.ts';
import { expect, historyGet, test } from './history-fixtures.ts';
import { until } from './support/sim.ts';
import { REPO_ROOT } from '../helpers/files.ts';
import { servoSdkPython } from '../helpers/servo-sdk-python.ts';

/** Reads an MCAP file with Foxglove's Python `mcap` library and prints what is in it. */
const MCAP_CHECK = path.join(REPO_ROOT, 'tests/helpers/mcap_check.py');

const NAMES = DEMO_ARM.servos.map((s) => s.name);
/** 45° as stored: the angle of the pulse the sim reports (whole µs), 44.955°. */
const ELBOW_45 = angleFromPwm(pwmFromAngle(45, 1), 1);

interface ChartProbe {
  labels: string[];
  points: number[];
  max: number[];
}
interface HistoryHook {
  __armtwin?: {
    history: { charts: Record<string, ChartProbe | undefined> };
    replay: {
      angles: Float64Array;
      record: object | null;
      clock: { position: number; playing: boolean };
    };
    viewer: { drawnWorld: { getObjectByName(n: string): unknown } };
  };
}

const chart = (page: Page, name: string) =>
  page.evaluate(
    (n) => (window as unknown as HistoryHook).__armtwin!.history.charts[n] ?? null,
    name,
  );

const replayPosition = (page: Page) =>
  page.evaluate(() => (window as unknown as HistoryHook).__armtwin!.replay.clock.position);

const replayAngle = (page: Page, i: number) =>
  page.evaluate((k) => (window as unknown as HistoryHook).__armtwin!.replay.angles[k]!, i);

/** The three.js sibling's URDF joint value of `joint`, in degrees (null while hidden). */
const siblingJointDeg = (page: Page, joint: string) =>
  page.evaluate((j) => {
    const hook = (window as unknown as HistoryHook).__armtwin!;
    const robot = hook.viewer.drawnWorld.getObjectByName('replay sibling') as
      { visible: boolean; joints: Record<string, { angle: number }> } | undefined;
    return robot?.visible ? (robot.joints[j]!.angle * 180) / Math.PI : null;
  }, joint);

async function moveElbow(page: Page, arm: { observer: { pwm: number[] } }, deg: number) {
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill(String(deg));
  const want = pwmFromAngle(deg, 1);
  await until(() => arm.observer.pwm[2] === want, 10_000, `the sim's elbow at ${want} µs`);
}

async function openHistory(page: Page) {
  await page.locator('summary', { hasText: 'History' }).click();
  await expect(page.getByRole('tab', { name: 'Charts' })).toBeVisible();
}

test('history: the panel shows what the simulator has just produced', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  await moveElbow(page, arm, 45);
  await arm.observer.fault({ fault: 'overheat', id: 2, celsius: 150 });
  // Wait until it is stored: an elbow temperature alarm and the elbow's tracking samples.
  await expect
    .poll(
      async () =>
        (
          await historyGet<{ episodes: { kind: string; id: string }[] }>(stack, 'alarms', {
            arm: arm.id,
            start: '-5m',
          })
        ).episodes
          .filter((e) => e.id === '002')
          .map((e) => e.kind),
      { timeout: 30_000 },
    )
    .toContain('temp-warning');

  await openHistory(page);
  await expect.poll(() => chart(page, 'temp'), { timeout: 15_000 }).not.toBeNull();
  const temp = (await chart(page, 'temp'))!;
  // The measured series first; the thermal model's predictions (dashed) follow.
  expect(temp.labels.slice(0, NAMES.length)).toEqual(NAMES);
  expect(Math.min(...temp.points.slice(0, NAMES.length))).toBeGreaterThan(0);
  expect(temp.max[2]).toBeGreaterThanOrEqual(60); // the overheating elbow
  expect(temp.max[0]).toBeLessThan(60);
  const volt = (await chart(page, 'volt'))!;
  expect(volt.labels.slice(0, NAMES.length)).toEqual(NAMES);
  expect(Math.min(...volt.points.slice(0, NAMES.length))).toBeGreaterThan(0);

  await page.getByLabel('Joint').selectOption('002');
  await expect
    .poll(async () => (await chart(page, 'angle'))?.labels ?? [], { timeout: 10_000 })
    .toEqual(['actual Elbow', 'commanded Elbow']);
  const angle = (await chart(page, 'angle'))!;
  expect(angle.points[0]).toBeGreaterThan(0);
  expect(angle.points[1]).toBeGreaterThan(0);
  expect(angle.max[0]).toBeGreaterThan(40); // mean windows: the move to 45° shows
  expect(angle.max[1]).toBeCloseTo(ELBOW_45, 6);
  await shot(page, testInfo, 'history-charts');
  await page.getByTestId('history-chart-angle').scrollIntoViewIfNeeded();
  await shot(page, testInfo, 'history-angle');

  // CSV of the temperature chart: built in the page, downloaded as a file.
  const [download] = await Promise.all([
    page.waitForEvent('download'),
    page.getByRole('button', { name: 'Download Temperature CSV' }).click(),
  ]);
  expect(download.suggestedFilename()).toMatch(new RegExp(`^armtwin-${arm.id}-temp-.*\\.csv$`));
  const csv = fs.readFileSync(await download.path(), 'utf8').split('\r\n');
  // The chart's columns: measured, then the thermal model's prediction of each servo.
  const predictedNames = NAMES.map((n) => `predicted ${n}`);
  expect(csv[0]).toBe(`time_ms,time_utc,${[...NAMES, ...predictedNames].join(',')}`);
  expect(csv.length).toBeGreaterThan(3);

  // The loaded range as MCAP, read back with Foxglove's own Python library: every servo's
  // samples, and joint states that have the elbow at 45°.
  const [mcap] = await Promise.all([
    page.waitForEvent('download'),
    page.getByRole('button', { name: 'Download MCAP' }).click(),
  ]);
  expect(mcap.suggestedFilename()).toMatch(new RegExp(`^${arm.id}-.*\\.mcap$`));
  const read = JSON.parse(
    execFileSync(servoSdkPython(), [MCAP_CHECK, await mcap.path()], {
      maxBuffer: 256 * 1024 * 1024,
    }).toString(),
  ) as {
    topics: Record<string, { schema: string; count: number }>;
    last_joint_states?: { joints: { name: string; position: number }[] };
  };
  for (const n of [0, 1, 2, 3, 4, 5])
    expect(read.topics[`/arm/${arm.id}/servo/00${n}`]?.count).toBeGreaterThan(0);
  expect(read.topics[`/${arm.id}/joint_states`]?.schema).toBe('foxglove.JointStates');
  expect(read.topics[`/${arm.id}/tf`]?.count).toBe(read.topics[`/${arm.id}/joint_states`]?.count);
  const elbow = read.last_joint_states?.joints.find((j) => j.name === 'elbow');
  expect((elbow!.position * 180) / Math.PI).toBeCloseTo(45, 0);

  await page.getByRole('tab', { name: 'Tracking, alarms & control' }).click();
  const elbowRow = page.getByTestId('tracking-002');
  await expect(elbowRow).toContainText('Elbow');
  expect(Number(await elbowRow.locator('td').last().textContent())).toBeGreaterThan(0);
  await expect(page.getByTestId('tracking-table')).toContainText('Base');
  const log = page.getByTestId('alarm-log');
  await expect(log).toContainText('temperature ≥ 60 °C');
  await expect(log.locator('tr', { hasText: 'temperature ≥ 60 °C' }).first()).toContainText(
    'Elbow',
  );
  await shot(page, testInfo, 'history-tables');
});

test('history: servos stored by an earlier profile under this arm id are named, not drawn', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  // An earlier 7-axis robot under the same arm id left servos 006 and 007 in storage.
  const earlier = encodeGroup([encodeHealth(6, 31, 7300), encodeHealth(7, 32, 7300)]);
  await arm.observer.client.publishAsync(`arm/${arm.id}/status`, earlier, { qos: 1 });
  await expect
    .poll(
      async () =>
        (
          await historyGet<{ series: { id: string }[] }>(stack, 'series', {
            arm: arm.id,
            start: '-5m',
            field: 'temp',
          })
        ).series.map((x) => x.id),
      { timeout: 30_000 },
    )
    .toContain('007');
  await openHistory(page);
  await expect.poll(() => chart(page, 'temp'), { timeout: 15_000 }).not.toBeNull();
  const predicted = NAMES.map((n) => `predicted ${n}`);
  expect((await chart(page, 'temp'))!.labels).toEqual([...NAMES, ...predicted]);
  expect((await chart(page, 'volt'))!.labels).toEqual([...NAMES, ...predicted]);
  await expect(page.getByTestId('history-others')).toHaveText(
    `Not shown: servos 006, 007, recorded under ${arm.id} but not in its current profile (armtwin5).`,
  );
  await shot(page, testInfo, 'history-others');
});

test('history: the control log shows who took and released control, and downloads as CSV', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  // The demo has no users file: alice's name is her own claim (SECURITY.md). The simulated arm
  // publishes the events; the middleware stores them.
  const stored = async () =>
    (
      await historyGet<{ events: { kind: string; by: string }[] }>(stack, 'audit', {
        arm: arm.id,
        start: '-5m',
      })
    ).events.map((e) => `${e.kind} ${e.by}`);
  await arm.observer.client.publishAsync(`arm/${arm.id}/claim/alice`, 'take', { qos: 1 });
  // Released once the take is stored: the two events have distinct times (rows to tell apart
  // on the replay's time axis below).
  await expect.poll(stored, { timeout: 30_000 }).toEqual(['taken alice']);
  await arm.observer.client.publishAsync(`arm/${arm.id}/claim/alice`, 'release', { qos: 1 });
  await expect.poll(stored, { timeout: 30_000 }).toEqual(['taken alice', 'released alice']);
  await openHistory(page);
  await page.getByRole('tab', { name: 'Tracking, alarms & control' }).click();
  const log = page.getByTestId('control-log');
  const rows = log.locator('tbody tr');
  await expect(rows).toHaveCount(2);
  await expect(rows.first()).toContainText('alice');

  // One timeline, both ways: a row's time moves the replay there (loading it), and the row at
  // the replay's instant — the last at or before it — is marked as the replay is scrubbed.
  const [taken, released] = (
    await historyGet<{ events: { at: number }[] }>(stack, 'audit', { arm: arm.id, start: '-5m' })
  ).events.map((e) => e.at);
  const marked = () =>
    rows.evaluateAll((trs) => trs.map((tr) => tr.getAttribute('aria-current') === 'time'));
  await expect(page.getByTestId('tables-replay-hint')).toBeVisible();
  expect(await marked()).toEqual([false, false]);
  await rows.nth(1).getByRole('button').click();
  await expect.poll(() => replayPosition(page)).toBe(released);
  await expect.poll(marked).toEqual([false, true]);
  await rows.nth(0).getByRole('button').click();
  await expect.poll(() => replayPosition(page)).toBe(taken);
  await expect.poll(marked).toEqual([true, false]);
  const scrubber = page.getByRole('slider', { name: 'Replay position' });
  await scrubber.fill(String(released!));
  await expect.poll(marked).toEqual([false, true]);
  await scrubber.fill(String(taken! - 1000)); // before the first event: no row
  await expect.poll(marked).toEqual([false, false]);
  await expect(scrubber).toBeFocused(); // the marker never takes the focus
  await scrubber.fill(String(taken!));
  await expect.poll(marked).toEqual([true, false]);
  await shot(page, testInfo, 'history-control-log-replay');
  const download = page.waitForEvent('download');
  await page.getByRole('button', { name: 'Download control log CSV' }).click();
  const csv = fs.readFileSync(await (await download).path(), 'utf8');
  expect(csv.split(/\r?\n/)[0]).toBe('time_utc,by,kind,detail');
  expect(csv).toContain(',alice,taken,');
  await shot(page, testInfo, 'history-control-log');
});

test('history: an API failure is shown as text, not a blank panel', async ({ hud }, testInfo) => {
  const { page } = hud;
  await page.route('**/api/history/**', (route) =>
    route.fulfill({
      status: 503,
      contentType: 'application/json',
      body: JSON.stringify({ error: 'history needs storage: set INFLUX_URL' }),
    }),
  );
  await openHistory(page);
  await expect(page.getByRole('alert').filter({ hasText: 'History is not available' })).toHaveCount(
    4, // temperature, voltage, power (the thermal model), angle
  );
  await page.getByRole('tab', { name: 'Tracking, alarms & control' }).click();
  await expect(page.getByRole('alert').filter({ hasText: 'history needs storage' })).toHaveCount(3);
  await shot(page, testInfo, 'history-error');
});

test.describe('replay on the page', () => {
  // Reads the sibling's three.js object, which only a main-thread view holds on the page.
  test.use({ hudQuery: '&render=main' });

  test('replay: the sibling arm takes the recorded poses', async ({
    hud,
    arm,
    stack,
  }, testInfo) => {
    const { page } = hud;
    await page.waitForTimeout(1500); // a moment recorded at home (0°)
    const before = Date.now();
    await moveElbow(page, arm, 45);
    await page.waitForTimeout(1000);
    await expect
      .poll(
        async () =>
          (
            await historyGet<{ angles: (number | null)[][] }>(stack, 'pose', {
              arm: arm.id,
              id: '002',
              start: '-5m',
            })
          ).angles.at(-1)?.[0] ?? null,
        { timeout: 15_000 },
      )
      .toBe(ELBOW_45);

    await openHistory(page);
    await page.getByRole('tab', { name: 'Replay' }).click();
    await page.getByRole('button', { name: 'Load replay' }).click();
    await expect(page.getByTestId('replay-angles')).toBeVisible();
    const scrubber = page.getByRole('slider', { name: 'Replay position' });

    // Scrub to before the move: the sibling's elbow is at 0 while the live arm is at 45.
    await scrubber.fill(String(before - 1000));
    await expect.poll(() => replayAngle(page, 2)).toBeCloseTo(0, 1);
    await expect.poll(() => siblingJointDeg(page, 'elbow')).toBeCloseTo(0, 1);
    await shot(page, testInfo, 'replay-before-move');

    // Play at 8×: the sibling follows the record to 45°.
    await page.getByLabel('Replay speed').selectOption('8');
    await page.getByRole('button', { name: 'Play', exact: true }).click();
    await expect.poll(() => replayAngle(page, 2), { timeout: 10_000 }).toBeCloseTo(ELBOW_45, 3);
    await expect.poll(() => siblingJointDeg(page, 'elbow')).toBeCloseTo(ELBOW_45, 3);
    const position = await page.evaluate(
      () => (window as unknown as HistoryHook).__armtwin!.replay.clock.position,
    );
    expect(position).toBeGreaterThan(before);
    // At 8× the few seconds to the end of the record pass in well under a second: it stops there.
    await expect(page.getByRole('button', { name: 'Play', exact: true })).toBeVisible();
    await expect(page.getByTestId('replay-angles')).toContainText('Elbow 45.0°');
    await shot(page, testInfo, 'replay-after-move');

    // Scrubbing back moves it back.
    await scrubber.fill(String(before - 500));
    await expect.poll(() => replayAngle(page, 2)).toBeCloseTo(0, 1);
    await page.getByRole('button', { name: 'Close', exact: true }).click();
    await expect.poll(() => siblingJointDeg(page, 'elbow')).toBeNull();
  });
});
