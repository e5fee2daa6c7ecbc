/**
 * The fleet section's table rows for one broker's ramp (../fleet.ts): the highest step that
 * stored every arm's points and the step after it with what it lost; CPU (ms per arm-second)
 * and memory (MiB per arm, marginal over the 1-arm step) of the simulators, the broker and the
 * middleware at that step; whether one simulator process held the rate.
 */
import { RATE_HELD, type ArmLoss } from './fleet-steps.ts';
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
  /** State samples a second each arm published over the window: the slowest arm, the median; which arm was slowest, how many arms fell short. */
  rateHz: { min: number; median: number; slowest?: string; short?: number };
  /** State payloads (messages) a second each arm published: below the samples when batched. */
  payloadHz: { min: number; median: number };
  /** Status messages the arms published over the window, and those the bare subscriber saw then (what the broker delivered). */
  publishedMessages: number;
  seenMessages: number;
  middlewareMessages: number;
  /** Servo points the arms' samples make, and those InfluxDB holds, over the step's life. */
  published: number;
  stored: number;
  lost: number;
  extra: number;
  worstArms: ArmLoss[];
  dropped: number;
  /** Seconds from the arms stopped to every point stored, and its limit. */
  drainS: number;
  drainLimitS: number;
  /** CPU, share of a core; resident memory, MiB (the simulators: all their processes). */
  cpuShare: Part;
  rssMiB: Part;
  pass: boolean;
  why: string;
  /** The same step in fewer processes first, when it fell short of the rate there alone. */
  firstTry?: {
    processes: number;
    rateHz: FleetStep['rateHz'];
    payloadHz: FleetStep['payloadHz'];
    why: string;
  };
}

const PARTS = { sims: 'simulators', broker: 'broker', middleware: 'middleware' } as const;

/**
 * CPU ms per arm-second and marginal MiB per arm of one part at a step: its memory beyond what
 * the 1-arm step's process took, once per simulator process.
 */
export function perArm(s: FleetStep, first: FleetStep, k: keyof Part): string {
  const ms = (s.cpuShare[k] * 1000) / s.arms;
  const n = k === 'sims' ? s.processes : 1;
  const mib =
    s.arms > n * first.arms ? (s.rssMiB[k] - n * first.rssMiB[k]) / (s.arms - n * first.arms) : NaN;
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
        ? `${best.arms} (${best.stored} of ${best.published} points, stored ${fmt(best.drainS, 1)} s after the arms stopped; in the window the arms sent ${best.publishedMessages} messages, a bare subscriber got ${best.seenMessages})`
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
  const tries = steps.flatMap((s) => (s.firstTry ? [{ ...s, ...s.firstTry }, s] : [s]));
  const heldAlone = tries
    .filter((s) => s.processes === 1 && s.rateHz.min >= RATE_HELD * rateHz)
    .at(-1);
  rows.push({
    figure: `${broker}: simulators at ${rateHz} Hz: most arms one process held; each step's slowest / median arm, samples/s (messages/s)`,
    value: heldAlone ? `${heldAlone.arms} arms in one process` : 'none',
    baseline: tries
      .map(
        (s) =>
          `${s.arms} arms in ${s.processes}: ${fmt(s.rateHz.min, 1)} / ${fmt(s.rateHz.median, 1)} (${fmt(s.payloadHz.min, 1)} / ${fmt(s.payloadHz.median, 1)})`,
      )
      .join('; '),
    target: 'reported',
    met: null,
  });
  return rows;
}
