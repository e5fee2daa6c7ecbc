/// <reference lib="dom" />
/**
 * A leader arm drawn as the ghost, end to end: an SO-101 leader on its own emulated Feetech bus
 * (`armtwin sim --bus feetech --hand` on a socat pty pair, its shafts moved by lines on stdin),
 * read by the real leader gateway (`armtwin gateway --bus feetech --leader-of ARM --user alice`)
 * driving a simulated SO-101 follower through its controller, on a real Mosquitto; the built HUD
 * in Chromium on the follower. Shown: the page's ghost goes where the leader is put (labelled with
 * alice's name) while the follower follows; the page's emergency stop stops the follower, the
 * page says alice's leader no longer drives the arm, and the ghost still shows the leader, now
 * away from the arm that stays.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import type { Page } from '@playwright/test';
import { expect, test } from './fixtures.ts';
import { ArmObserver, startSim, until, type SimProcess } from './support/sim.ts';
import { joints } from './support/robots-window.ts';
import { so101BusLine, type SerialLine } from '../integration/serial-line.ts';
import { armtwin, type Child } from '../integration/sim-helpers.ts';

const USER = 'alice';
const rad = (deg: number) => (deg * Math.PI) / 180;
/** The page's ghost (or live arm) shoulder_pan, degrees. */
const pan = async (page: Page, which: 'robot' | 'ghost') =>
  ((await joints(page, which))[0]! * 180) / Math.PI;

let arm: string;
let follower: SimProcess;
let observer: ArmObserver;
let leader: SerialLine;
let gateway: Child;
let dir: string;

test.beforeEach(async ({ stack }, testInfo) => {
  test.setTimeout(120_000);
  arm = `leader-${process.pid}`;
  dir = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-leader-ghost-'));
  observer = await ArmObserver.connect(stack.broker.url, arm);
  follower = startSim(stack.broker.url, arm, testInfo.outputPath('follower.log'), [
    ...['--profile', 'so101', '--report', 'angle', '--rate', '50'],
  ]);
  await until(
    () =>
      observer.online === '1' &&
      [1, 2, 3, 4, 5, 6].every((id) => observer.angles[id] !== undefined),
    30_000,
    'the simulated SO-101 follower online',
  );
  leader = so101BusLine(dir, 'leader', { hand: true });
  await leader.start();
  gateway = armtwin([
    ...['gateway', '--bus', 'feetech', '--serial', leader.hostSide, '--baud', '1000000'],
    ...['--profile', 'so101', '--leader-of', arm, '--user', USER, '--rate', '30'],
    ...['--mqtt', stack.broker.url],
  ]);
});

// eslint-disable-next-line no-empty-pattern
test.afterEach(async ({}, testInfo) => {
  await testInfo.attach('leader-gateway.log', { body: gateway?.output() ?? '' });
  await gateway?.stop();
  await leader?.stop();
  await follower?.stop();
  await observer?.close();
  fs.rmSync(dir, { recursive: true, force: true });
});

test("the ghost shows the leader's pose as the follower follows; after the page's e-stop the page says the leader no longer drives", async ({
  page,
  stack,
}) => {
  page.on('pageerror', (err) => console.error(`[page error] ${err.message}`));
  await page.goto(
    `${stack.web.url}?broker=${encodeURIComponent(stack.broker.wsUrl)}&arm=${arm}&role=operator&render=main`,
  );
  await page.waitForFunction(
    () => (window as unknown as { __armtwin?: { ready?: boolean } }).__armtwin?.ready === true,
    null,
    { timeout: 30_000 },
  );
  const leaderLine = page.getByTestId(`leader-${USER}`);
  await expect(leaderLine).toHaveText(`${USER}'s leader arm drives the arm`, { timeout: 20_000 });

  // The leader moved by hand: the ghost goes there, the follower follows.
  leader.hand('1:-20,2:15');
  await expect.poll(() => pan(page, 'ghost'), { timeout: 20_000 }).toBeCloseTo(-20, 0);
  await expect
    .poll(async () => (await joints(page, 'ghost'))[1]!, { timeout: 10_000 })
    .toBeCloseTo(rad(15), 2);
  await expect(page.getByTestId('ghost-shows')).toContainText(
    `showing ${USER}'s leader arm: where it asks the arm to go`,
  );
  await until(() => Math.abs(observer.angles[1]! + 20) < 0.5, 20_000, 'the follower at −20°');
  await expect.poll(() => pan(page, 'robot'), { timeout: 10_000 }).toBeCloseTo(-20, 0);

  // The page's emergency stop: the leader no longer drives the arm, and the page says so.
  await page.getByRole('button', { name: 'Emergency stop' }).click();
  await expect(leaderLine).toContainText(`${USER}'s leader arm no longer drives the arm`, {
    timeout: 20_000,
  });
  await expect(leaderLine).toContainText('emergency stop');
  await expect(leaderLine).toHaveAttribute('data-following', 'false');
  const stopped = observer.angles[1]!;

  // The leader goes on: the ghost shows it where it now is, the follower stays.
  leader.hand('1:-40');
  await expect.poll(() => pan(page, 'ghost'), { timeout: 20_000 }).toBeCloseTo(-40, 0);
  await page.waitForTimeout(1000);
  expect(Math.abs(observer.angles[1]! - stopped)).toBeLessThan(0.5);
  expect(Math.abs((await pan(page, 'robot')) - stopped)).toBeLessThan(0.5);
});
