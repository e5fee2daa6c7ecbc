/**
 * The fleet section's table rows for one broker's ramp (../fleet.ts): the highest step that
 * stored every arm's points and the step after it with what it lost; CPU (ms per arm-second)
 * and memory (MiB per arm, marginal over the 1-arm step) of the simulators, the broker and the
 * middleware at that step; whether one simulator process held the rate.
 */
import type { ArmLoss } from './fleet-steps.ts';
import { fmt, type Row } from './types.ts';

export interface Part {
  sims: number;
  broker: number;
  middleware: number;
}

export interface FleetStep {
  arms: number;
  /** Simulator processes the arms were spread over. */
  processes: number;
  windowS: number;
  /** State samples a second each arm published over the window: the slowest arm, the median. */
  rateHz: { min: number; median: number };
  /** Status messages the bare subscriber saw over the window (what the broker delivered). */
  seenMessages: number;
  middlewareMessages: number;
  /** Servo points the arms' samples make, and those InfluxDB holds, over the step's life. */
  published: number;
  stored: number;
  lost: number;
  extra: number;
  worstArms: ArmLoss[];
  dropped: number;
  /** CPU, share of a core; resident memory, MiB (the simulators: all their processes). */
  cpuShare: Part;
  rssMiB: Part;
  pass: boolean;
  why: string;
}

const PARTS = { sims: 'simulators', broker: 'broker', middleware: 'middleware' } as const;

/** CPU ms per arm-second and marginal MiB per arm of one part at a step. */
export function perArm(s: FleetStep, first: FleetStep, k: keyof Part): string {
  const ms = (s.cpuShare[k] * 1000) / s.arms;
  const mib = s.arms > first.arms ? (s.rssMiB[k] - first.rssMiB[k]) / (s.arms - first.arms) : NaN;
  return `${fmt(ms, 2)} ms CPU per arm-second, ${fmt(mib, 2)} MiB per arm (${fmt(s.rssMiB[k], 0)} MiB in all)`;
}

export function fleetRows(
  broker: string,
  steps: FleetStep[],
  best: FleetStep | undefined,
  rateHz: number,
): Row[] {
  const first = steps[0];
  const next = steps[best ? steps.indexOf(best) + 1 : 0];
  const lost = (s: FleetStep) =>
    `${s.arms} arms (${s.processes} sim process${s.processes > 1 ? 'es' : ''}): ${s.why}`;
  const rows: Row[] = [
    {
      figure: `Arms at ${rateHz} Hz through ${broker} into the middleware and InfluxDB: highest step with every arm's points stored, each arm ≥ 95 % of the rate`,
      value: best
        ? `${best.arms} (${best.stored} of ${best.published} points; slowest arm ${fmt(best.rateHz.min, 1)} Hz)`
        : 'none',
      baseline: next ? `next step ${lost(next)}` : 'no step failed',
      target: 'reported',
      met: null,
    },
  ];
  if (!best || !first) return rows;
  for (const k of Object.keys(PARTS) as (keyof Part)[])
    rows.push({
      figure: `${broker}: ${PARTS[k]} per arm at ${best.arms} arms`,
      value: perArm(best, first, k),
      baseline: `1 arm: ${fmt(first.cpuShare[k] * 1000, 2)} ms CPU a second, ${fmt(first.rssMiB[k], 0)} MiB`,
      target: 'reported',
      met: null,
    });
  const single = steps.filter((s) => s.processes === 1);
  const heldAlone = single.filter((s) => s.rateHz.min >= 0.95 * rateHz).at(-1);
  rows.push({
    figure: `${broker}: one simulator process at ${rateHz} Hz, most arms it held (then one process per core)`,
    value: heldAlone ? `${heldAlone.arms} arms` : 'none',
    baseline: `steps: ${steps.map((s) => `${s.arms} arms ${s.processes}p ${fmt(s.rateHz.min, 1)}/${fmt(s.rateHz.median, 1)} Hz`).join(', ')} (slowest/median arm)`,
    target: 'reported',
    met: null,
  });
  return rows;
}
