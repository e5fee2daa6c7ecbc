/// <reference lib="dom" />
/**
 * Keep-out zones, checked twice (docs/protocol.md, "Keep-out zones"): armtwin5 with a table
 * declared in its profile (a models folder of the test's own, given to `armtwin sim --models`).
 * The page draws the table, refuses a Cartesian target through it (the ghost's offending link red,
 * the reason in words) and sends nothing; the same target sent past the page, raw on
 * `arm/{id}/control`, is refused by the simulator (`$KMS:25!`, `$ERR:… zone …`), and the arm
 * never moves.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { solveIk } from '@armtwin/ik';
import { pwmFromAngle } from '@armtwin/protocol';
import { REPO_ROOT } from '../helpers/services.ts';
import { expect, shot, test } from './fixtures.ts';
import { until } from './support/sim.ts';

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };
/** A target 20 mm under the table top, above the floor: the IK reaches it, the zone refuses it. */
const THROUGH = { x: 250, y: 0, z: 10 };

// The profile keeps armtwin5's name, so the page draws it with the URDF it serves.
const models = path.join(os.tmpdir(), `armtwin-e2e-zones-${process.pid}`);
const dir = path.join(models, 'armtwin5');
fs.rmSync(models, { recursive: true, force: true });
fs.cpSync(path.join(REPO_ROOT, 'public/models/armtwin5'), dir, { recursive: true });
const profile = JSON.parse(fs.readFileSync(path.join(dir, 'profile.json'), 'utf8')) as object;
fs.writeFileSync(
  path.join(dir, 'profile.json'),
  JSON.stringify({ ...profile, keepOut: { zones: [TABLE] } }),
);
test.afterAll(() => fs.rmSync(models, { recursive: true, force: true }));
test.use({ simArgs: ['--models', models] });

interface ZonesWindow {
  __armtwin: { viewer: { zones: { names: string[] }; ghostPainted: string } };
}

test('a target through the table is refused in the page, and again by the simulator', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  // The table comes with the announced profile and is drawn in the 3D view.
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.zones.names),
    )
    .toEqual(['table']);
  const home = [...arm.observer.pwm];
  expect(home.slice(0, 4)).toEqual([1500, 1500, 1500, 1500]);
  const since = Date.now();

  // In the page: the preview names the link and the zone, the ghost paints that link red,
  // and Move sends nothing.
  await page.getByLabel('X', { exact: true }).fill(String(THROUGH.x));
  await page.getByLabel('Y', { exact: true }).fill(String(THROUGH.y));
  await page.getByLabel('Z', { exact: true }).fill(String(THROUGH.z));
  await expect(page.getByTestId('ik-preview')).toHaveText(
    /^Unreachable: (on the way: )?(hand|forearm) \d+\.\d mm into zone "table" \(code 25\)\.$/,
  );
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.ghostPainted),
    )
    .toMatch(/^(wrist_pitch|elbow)$/);
  await shot(page, testInfo, 'zone-refused-in-page');
  await page.getByRole('button', { name: 'Move', exact: true }).click();
  await expect(page.getByTestId('kms-refusal')).toHaveText(
    /^Not sent: (on the way: )?(hand|forearm) \d+\.\d mm into zone "table" \(code 25\)\.$/,
  );
  expect(arm.observer.commands(since)).toEqual([]);

  // Past the page: the same target as `$KMS`, and as the pulses of its IK solution.
  const kms = arm.observer.kmsReplies.length;
  await arm.observer.client.publishAsync(
    `arm/${arm.id}/control`,
    `$KMS:${THROUGH.x},${THROUGH.y},${THROUGH.z},1000!`,
    { qos: 1 },
  );
  await until(() => arm.observer.kmsReplies.length > kms, 10_000, 'the $KMS reply');
  expect(arm.observer.kmsReplies.at(-1)).toBe(25);
  const ik = solveIk(THROUGH.x, THROUGH.y, THROUGH.z);
  expect(ik.code).toBe(0);
  const group = `{${ik.pwm.map((p, i) => `#00${i}P${String(p).padStart(4, '0')}T1000!`).join('')}}`;
  await arm.observer.client.publishAsync(`arm/${arm.id}/control`, group, { qos: 1 });
  const err = await until(
    () => arm.observer.messages.find((m) => m.at >= since && m.text.includes('$ERR:')),
    10_000,
    'the $ERR reply',
  );
  expect(err.text).toMatch(/\$ERR:group rejected: zone: (hand|forearm) in "table"( on the way)?!/);

  // Nothing moved: a second's worth of status later, the arm is where it was.
  const seen = arm.observer.messages.length;
  await until(() => arm.observer.messages.length > seen + 20, 10_000, 'more status');
  expect(arm.observer.pwm.slice(0, 4)).toEqual(home.slice(0, 4));
  await shot(page, testInfo, 'zone-refused-by-sim');
});

test('a jog that would put the hand into the table is not sent; the ghost shows it, hand red', async ({
  hud,
  arm,
}, testInfo) => {
  const { page } = hud;
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.zones.names),
    )
    .toEqual(['table']);
  // Upper arm at 45°, forearm level: clear of the table, sent, and the arm goes there.
  for (const [name, i] of [
    ['Shoulder', 1],
    ['Elbow', 2],
  ] as const) {
    await page.getByRole('slider', { name, exact: true }).fill('-45');
    const at = pwmFromAngle(-45, 1);
    await until(() => arm.observer.pwm[i] === at, 10_000, `${name} at ${at} µs`);
  }
  const since = Date.now();
  // The hand pointing down from there would go into the table.
  await page.getByRole('slider', { name: 'Wrist pitch', exact: true }).fill('-90');
  await expect(page.getByTestId('jog-refusal')).toHaveText(
    /^Not sent: hand \d+\.\d mm into zone "table"\.$/,
  );
  await expect
    .poll(() =>
      page.evaluate(() => (window as unknown as ZonesWindow).__armtwin.viewer.ghostPainted),
    )
    .toBe('wrist_pitch');
  await expect(page.getByTestId('ghost-shows')).toContainText('refused jog');
  expect(arm.observer.commands(since)).toEqual([]);
  await shot(page, testInfo, 'jog-refused');
});
