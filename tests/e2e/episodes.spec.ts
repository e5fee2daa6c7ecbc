/// <reference lib="dom" />
/**
 * Episodes from the HUD (History panel, Episodes tab) end to end: real Mosquitto, the real
 * simulator, the real middleware writing to a real influxd, the built HUD in Chromium
 * (./history-fixtures.ts; the anonymous local demo, so the page may mark). An operator records
 * an episode while moving the arm, stops it and finds it listed with its task; the stored range
 * holds the move, and its Replay plays it on the sibling. Discard (the recording one, or a listed one) removes it; the loaded range can
 * be marked afterwards; a mark made elsewhere shows in the open tab. The viewer's side (no buttons, the reason) is in roles-middleware.spec.
 */
import type { Page } from '@playwright/test';
import type { EpisodeMark, PoseAnswer } from '@armtwin/api';
import { pwmFromAngle } from '@armtwin/protocol';
import { shot } from './fixtures.ts';
import { expect, historyGet, test, type StorageStack } from './history-fixtures.ts';
import { until } from './support/sim.ts';

interface ReplayHook {
  __armtwin?: {
    replay: {
      angles: Float64Array;
      record: { times: number[]; start: number; stop: number } | null;
      seek(t: number): void;
    };
  };
}

async function episodesOf(stack: StorageStack, arm: string): Promise<EpisodeMark[]> {
  const res = await fetch(`${stack.apiUrl}/arms/${arm}/episodes`);
  expect(res.status).toBe(200);
  return ((await res.json()) as { episodes: EpisodeMark[] }).episodes;
}

async function moveElbow(page: Page, arm: { observer: { pwm: number[] } }, deg: number) {
  await page.getByRole('slider', { name: 'Elbow', exact: true }).fill(String(deg));
  const want = pwmFromAngle(deg, 1);
  await until(() => arm.observer.pwm[2] === want, 10_000, `the sim's elbow at ${want} µs`);
}

test('episodes: record while moving, stop, listed with its task; discard removes it', async ({
  hud,
  arm,
  stack,
}, testInfo) => {
  const { page } = hud;
  await page.locator('summary', { hasText: 'History' }).click();
  await page.getByRole('tab', { name: 'Episodes' }).click();
  const list = page.getByRole('list', { name: 'Episodes' });
  await expect(page.getByText('No episode yet.')).toBeVisible();

  const task = page.getByRole('textbox', { name: 'Episode task' });
  await expect(page.getByRole('button', { name: 'Record' })).toBeDisabled(); // no task yet
  await task.fill('lift the elbow to 45°');
  await page.getByRole('button', { name: 'Record' }).click();
  await expect(page.getByTestId('episodes-note')).toHaveText('Recording "lift the elbow to 45°".');
  const timer = page.getByTestId('episode-recording');
  await expect(timer).toBeVisible();
  await expect(task).toBeDisabled();
  await moveElbow(page, arm, 45);
  await expect(timer).not.toHaveText('● 0:00', { timeout: 5000 }); // it runs
  await shot(page, testInfo, 'episode-recording');
  // Stop once the middleware has stored the elbow at 45° inside the open episode.
  const [open] = await episodesOf(stack, arm.id);
  const elbowMax = async (startMs: number, stopMs: number) => {
    const pose = await historyGet<PoseAnswer>(stack, 'pose', {
      arm: arm.id,
      start: new Date(startMs).toISOString(),
      stop: new Date(stopMs).toISOString(),
    });
    const elbow = pose.ids.indexOf('002');
    return Math.max(...pose.angles.map((a) => a[elbow] ?? -Infinity));
  };
  await expect
    .poll(() => elbowMax(open!.startMs, Date.now()), { timeout: 15_000 })
    .toBeGreaterThan(44);
  await page.getByRole('button', { name: 'Stop', exact: true }).click();
  await expect(page.getByTestId('episodes-note')).toContainText('Kept "lift the elbow to 45°"');
  await expect(timer).toBeHidden();
  await expect(list.getByTestId('episode')).toHaveCount(1);
  await expect(list.getByTestId('episode')).toContainText('lift the elbow to 45°');
  await expect(list.getByTestId('episode')).toContainText('by anonymous');
  await shot(page, testInfo, 'episode-listed');

  // What the middleware keeps: the episode, and the move inside its range.
  const [kept] = await episodesOf(stack, arm.id);
  expect(kept).toMatchObject({ task: 'lift the elbow to 45°', by: 'anonymous', discarded: false });
  expect(kept!.startMs).toBe(open!.startMs);
  expect(await elbowMax(kept!.startMs, kept!.stopMs!)).toBeGreaterThan(44);

  // Replay from the list: the History range becomes the episode's, the sibling replays the move.
  await list.getByRole('button', { name: 'Replay episode lift the elbow to 45°' }).click();
  await expect(page.getByRole('tab', { name: 'Replay' })).toHaveAttribute('aria-selected', 'true');
  await page.waitForFunction(() => (window as unknown as ReplayHook).__armtwin!.replay.record);
  const replayed = await page.evaluate(() => {
    const replay = (window as unknown as ReplayHook).__armtwin!.replay;
    const rec = replay.record!;
    replay.seek(rec.times.at(-1)!);
    return { start: rec.start, stop: rec.stop };
  });
  expect(replayed.start).toBeGreaterThanOrEqual(kept!.startMs);
  expect(replayed.stop).toBeLessThanOrEqual(kept!.stopMs!);
  await expect
    .poll(() => page.evaluate(() => (window as unknown as ReplayHook).__armtwin!.replay.angles[2]))
    .toBeGreaterThan(44);
  await page.getByRole('tab', { name: 'Episodes' }).click();

  // A second one, discarded while it records: never listed.
  await task.fill('a false start');
  await page.getByRole('button', { name: 'Record' }).click();
  await expect(timer).toBeVisible();
  await page.getByRole('button', { name: 'Discard', exact: true }).click();
  await expect(page.getByTestId('episodes-note')).toHaveText('Discarded "a false start".');
  await expect(list.getByTestId('episode')).toHaveCount(1);

  // Afterwards: the loaded range (History's 5 min) marked as an episode, then discarded again.
  // The loaded range is the replayed episode's now: marking it again is refused, saying why.
  await task.fill('the whole morning');
  await page.getByRole('button', { name: 'Mark loaded range' }).click();
  await expect(page.getByTestId('episodes-note')).toContainText(
    'Refused (HTTP 409): an episode already starts at',
  );
  const episodeRange = await page.getByTestId('history-range').textContent();
  await page.getByRole('radio', { name: '5 min' }).check();
  await expect(page.getByTestId('history-range')).not.toHaveText(episodeRange!);
  await page.getByRole('button', { name: 'Mark loaded range' }).click();
  await expect(list.getByTestId('episode')).toHaveCount(2);
  await expect(list).toContainText('the whole morning');
  await page.getByRole('button', { name: 'Discard episode the whole morning' }).click();
  await expect(list.getByTestId('episode')).toHaveCount(1);
  await expect(list).not.toContainText('the whole morning');
  // Marked elsewhere (the CLI, another page): the open tab follows.
  const post = (body: object) =>
    fetch(`${stack.apiUrl}/arms/${arm.id}/episodes`, {
      method: 'POST',
      headers: { 'content-type': 'application/json' },
      body: JSON.stringify(body),
    });
  expect((await post({ action: 'start', task: 'from the command line' })).status).toBe(201);
  await expect(timer).toBeVisible({ timeout: 15_000 });
  await expect(task).toHaveValue('from the command line');
  expect((await post({ action: 'discard' })).status).toBe(200);
  await expect(timer).toBeHidden({ timeout: 15_000 });

  const stored = await episodesOf(stack, arm.id);
  expect(stored.map((e) => [e.task, e.discarded])).toEqual([
    ['the whole morning', true],
    ['lift the elbow to 45°', false],
    ['a false start', true],
    ['from the command line', true],
  ]);
});
