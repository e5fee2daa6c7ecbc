import { describe, expect, it } from 'vitest';
import { fleetRows, perArm, type FleetStep } from '../lib/fleet-rows.ts';

function step(arms: number, processes: number, o: Partial<FleetStep> = {}): FleetStep {
  return {
    arms,
    processes,
    windowS: 5,
    rateHz: { min: 50, median: 50 },
    payloadHz: { min: 48, median: 49 },
    publishedMessages: arms * 250,
    seenMessages: arms * 250,
    middlewareMessages: arms * 260,
    published: arms * 1500,
    stored: arms * 1500,
    lost: 0,
    extra: 0,
    worstArms: [],
    dropped: 0,
    drainS: 1,
    drainLimitS: 3,
    cpuShare: { sims: arms * 0.002, broker: arms * 0.001, middleware: arms * 0.0015 },
    rssMiB: {
      sims: 120 * processes + arms * 0.5,
      broker: 10 + arms * 0.01,
      middleware: 160 + arms * 0.25,
    },
    pass: true,
    why: '',
    ...o,
  };
}

describe('perArm', () => {
  it('is CPU per arm-second and memory beyond each simulator process’s base', () => {
    const one = step(1, 1);
    // 2 processes of 100 arms: 240 MiB of bases, 50 MiB for the arms.
    expect(perArm(step(100, 2), one, 'sims')).toBe(
      '2.00 ms CPU per arm-second, 0.50 MiB per arm (290 MiB in all)',
    );
    expect(perArm(step(100, 2), one, 'middleware')).toBe(
      '1.50 ms CPU per arm-second, 0.25 MiB per arm (185 MiB in all)',
    );
  });
});

describe('fleetRows', () => {
  it('quotes the highest step that stored everything, and the next with why it failed', () => {
    const steps = [
      step(1, 1),
      step(50, 1, { payloadHz: { min: 30, median: 35 } }),
      step(100, 2, { pass: false, why: 'stored 9.0 s after the arms stopped (limit 4.0 s)' }),
    ];
    const rows = fleetRows('Mosquitto', steps, steps[1], 50);
    expect(rows[0]!.value).toMatch(/^50 \(75000 of 75000 points/);
    expect(rows[0]!.baseline).toBe(
      'next step 100 arms (2 sim processes): stored 9.0 s after the arms stopped (limit 4.0 s)',
    );
    expect(rows.at(-1)!.value).toBe('50 arms in one process');
  });

  it('says none when the first step failed', () => {
    const rows = fleetRows(
      'the embedded broker',
      [step(1, 1, { pass: false, why: 'x' })],
      undefined,
      50,
    );
    expect(rows).toHaveLength(1);
    expect(rows[0]!.value).toBe('none');
    expect(rows[0]!.baseline).toBe('next step 1 arms (1 sim process): x');
  });
});
