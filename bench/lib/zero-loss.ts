/**
 * The verdict on one step of a zero-loss ramp (ingest, Telegraf): why it failed, or '' when it
 * passed. A step passes when nothing is missing or dropped, the publisher kept at least 95 % of
 * the offered rate, and the backlog was written within the drain limit.
 */
export interface StepFacts {
  /** Offered rate, messages/s. */
  rate: number;
  /** Messages the publisher sent, and the seconds it took. */
  sent: number;
  sendS: number;
  /** Expected points (or frames) not stored, and points the consumer says it dropped. */
  missing: number;
  dropped?: number;
  /** What is missing is counted in these (`points`, `frames`). */
  unit: string;
  drainS: number;
  drainLimitS: number;
}

export function stepVerdict(f: StepFacts): string {
  const reached = f.sent / f.sendS;
  if (f.missing !== 0) return `${f.missing} ${f.unit} missing`;
  if (f.dropped) return `${f.dropped} dropped`;
  if (reached < 0.95 * f.rate) return `publisher reached ${Math.round(reached)}/s only`;
  if (f.drainS > f.drainLimitS) return `backlog took ${f.drainS.toFixed(1)} s to write`;
  return '';
}
