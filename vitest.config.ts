import { defineConfig } from 'vitest/config';

// `unit` (pure logic, fakes allowed, fast) and the integration tests (real Mosquitto / influxd /
// processes, started by tests/helpers; run both with `--project 'integration*'`). Integration
// files run three at a time: each starts its own services on free ports with its own temp
// folders, and most of their time is spent waiting on those processes. The serial-line files
// (a pty pair and an emulated servo bus answering within the protocol's timeouts) run after
// them, one at a time and alone: starved of CPU, a late reply reads as a broken bus.
const SERIAL_LINE = [
  'tests/integration/gateway-bus.test.ts',
  'tests/integration/gateway-pty.test.ts',
  'tests/integration/brokers-gateway.test.ts',
  'tests/integration/servo-bus-sdk.test.ts',
  'tests/integration/gateway-doctor.test.ts',
  'tests/integration/lerobot-plugin.test.ts',
  'tests/integration/up-so101.test.ts',
  'tests/integration/leader-teleop.test.ts',
];
const INTEGRATION = { testTimeout: 180_000, hookTimeout: 240_000 };

export default defineConfig({
  test: {
    projects: [
      {
        test: {
          name: 'unit',
          include: ['packages/*/test/**/*.test.ts', 'apps/*/test/**/*.test.ts', 'bench/test/**/*.test.ts'],
          // A budget, not a speed check: the property tests are CPU-bound, and on a loaded
          // 2-core machine one took 5.2 s against Vitest's default 5 s (fast-check in teach.test).
          testTimeout: 30_000,
        },
      },
      {
        test: {
          name: 'integration',
          include: ['tests/integration/**/*.test.ts'],
          exclude: SERIAL_LINE,
          ...INTEGRATION,
          maxWorkers: 3,
        },
      },
      {
        test: {
          name: 'integration-serial',
          include: SERIAL_LINE,
          ...INTEGRATION,
          fileParallelism: false,
          sequence: { groupOrder: 1 },
        },
      },
    ],
  },
});
