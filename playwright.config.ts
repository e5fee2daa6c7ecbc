import { defineConfig } from '@playwright/test';
import { CHROMIUM_ARGS, CHROMIUM_PATH } from './tests/helpers/chromium.ts';

/**
 * End-to-end tests drive the system Chromium (Debian package, installed by
 * scripts/install-deps.sh), not a Playwright-downloaded browser. Services (Mosquitto,
 * influxd) come from tests/helpers/services.ts; import that, never `vitest`, from e2e code.
 *
 * Two projects. `shared`: specs that run two at a time (each worker has its own broker and
 * web server, arms have unique ids), most of their time spent waiting on the stack.
 * `alone`: specs that judge the page frame by frame or pixel by pixel, drive an emulated
 * servo bus within its protocol's timeouts, or load the machine themselves (50 arms, a
 * flood, a 3-node cluster); scripts/test.sh runs them after `shared`, one at a time with nothing beside them.
 * Run both (`npx playwright test`) and `alone` runs beside `shared`, on one worker.
 */
const ALONE = [
  'hud-rate',
  'hold-jog',
  'predictive-twin',
  'render-worker',
  'camera-calibration',
  'calibration',
  'so101',
  'leader-ghost',
  'fleet-fifty',
  'flood',
  'ros2-hud',
  'history-video',
  'cluster-hud',
].map((name) => `**/${name}.spec.ts`);

export default defineConfig({
  testDir: 'tests/e2e',
  outputDir: 'test-results/e2e',
  fullyParallel: false,
  workers: 2,
  retries: 0,
  forbidOnly: true,
  timeout: 60_000,
  globalTimeout: 20 * 60_000,
  expect: { timeout: 10_000 },
  reporter: [
    ['list'],
    ['json', { outputFile: process.env.E2E_REPORT ?? 'test-results/e2e-results.json' }],
  ],
  projects: [
    { name: 'shared', testIgnore: ALONE },
    { name: 'alone', testMatch: ALONE, workers: 1 },
  ],
  use: {
    browserName: 'chromium',
    headless: true,
    viewport: { width: 1280, height: 800 },
    actionTimeout: 10_000,
    navigationTimeout: 30_000,
    screenshot: 'on',
    trace: 'retain-on-failure',
    launchOptions: {
      executablePath: CHROMIUM_PATH,
      args: CHROMIUM_ARGS,
    },
  },
});
