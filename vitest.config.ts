import { defineConfig } from 'vitest/config';

// Two projects: `unit` (pure logic, fakes allowed, fast) and `integration`
// (real Mosquitto / influxd / processes, started by tests/helpers). Integration files run three
// at a time: each starts its own services on free ports with its own temp folders, and most of
// their time is spent waiting on those processes, so a 2-core machine runs three side by side.
export default defineConfig({
  test: {
    projects: [
      {
        test: {
          name: 'unit',
          include: ['packages/*/test/**/*.test.ts', 'apps/*/test/**/*.test.ts', 'bench/test/**/*.test.ts'],
        },
      },
      {
        test: {
          name: 'integration',
          include: ['tests/integration/**/*.test.ts'],
          testTimeout: 180_000,
          hookTimeout: 240_000,
          maxWorkers: 3,
        },
      },
    ],
  },
});
