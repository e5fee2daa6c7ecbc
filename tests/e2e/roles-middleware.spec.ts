/// <reference lib="dom" />
/**
 * A deployment without `armtwin up` (Mosquitto, the HUD's `dist` served with `/api/` proxied to
 * the middleware): the middleware has the users file (ARMTWIN_USERS), so its `/whoami` tells
 * the page its role. A viewer's page has every control off and says why; an operator's page
 * may jog — with no `?role=` hint in either URL. The same for the History panel's episodes: a
 * viewer has no Record button and is told why.
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { expect, test } from './fixtures.ts';
import { freePort } from '../helpers/services.ts';
import {
  spawnMiddleware,
  type MiddlewareProcess,
} from '../../apps/middleware/test/support/harness.ts';
import { HUD_DIST } from './support/build-hud.ts';
import { serveStatic, type StaticServer } from './support/static-server.ts';
import { USERS_FILE, password } from '../integration/auth-cases.ts';

let mw: MiddlewareProcess;
let web: StaticServer;
let spool = '';

test.beforeEach(async ({ stack }, testInfo) => {
  spool = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-e2e-roles-'));
  mw = await spawnMiddleware(
    {
      MQTT_URL: stack.broker.url,
      MQTT_CLIENT_ID: `e2e-roles-${process.pid}`,
      SPOOL_DIR: spool,
      ARMTWIN_USERS: USERS_FILE,
      API_TOKEN: 'e2e-roles-token',
    },
    await freePort(),
    testInfo.outputPath('middleware.log'),
  );
  web = await serveStatic(HUD_DIST, {
    proxy: { prefix: '/api/', target: `http://127.0.0.1:${mw.port}` },
  });
});

test.afterEach(async () => {
  await web?.close();
  await mw?.stop();
  fs.rmSync(spool, { recursive: true, force: true });
});

for (const user of ['viewer', 'operator'] as const) {
  test(`the middleware's /whoami gives the page its role: ${user}`, async ({
    page,
    stack,
    arm,
  }) => {
    const q = new URLSearchParams({
      broker: stack.broker.wsUrl,
      arm: arm.id,
      user,
      password: password(user),
    });
    await page.goto(`${web.url}?${q}`);
    await expect(page.getByTestId('signed-in-as')).toHaveText(`Signed in as ${user}, ${user}.`);
    await expect(page.getByTestId('freshness')).toHaveText('Data is live.');
    const slider = page.getByRole('slider', { name: 'Base', exact: true });
    if (user === 'viewer') {
      await expect(slider).toBeDisabled();
      await expect(page.getByTestId('role-reason')).toContainText(
        'Signed in as viewer: controls are disabled.',
      );
    } else {
      await expect(slider).toBeEnabled();
      await expect(page.getByRole('button', { name: 'Emergency stop' })).toBeEnabled();
    }
    // Episodes (History panel): a viewer sees no Record button, and is told why.
    await page.locator('summary', { hasText: 'History' }).click();
    await page.getByRole('tab', { name: 'Episodes' }).click();
    const record = page.getByRole('button', { name: 'Record', exact: true });
    if (user === 'viewer') {
      await expect(page.getByTestId('episodes-reason')).toContainText(
        'Recording episodes needs an operator account.',
      );
      await expect(record).toHaveCount(0);
      await expect(page.getByRole('textbox', { name: 'Episode task' })).toHaveCount(0);
    } else {
      await expect(record).toBeVisible();
      await expect(page.getByTestId('episodes-reason')).toHaveCount(0);
    }
  });
}
