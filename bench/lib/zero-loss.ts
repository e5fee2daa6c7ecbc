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

/**
 * The ratio of two consumers' highest zero-loss rates, `a ÷ b`, when a ramp may have ended at a
 * consumer's own limit (`limit`: its last step failed on its own, missing points or a backlog)
 * or not (the publisher's limit, the list's end: its rate is only a lower bound). Both at their
 * limits: the ratio. Only `b` at its limit: a lower bound, `≥`. Only `a`: an upper bound, `≤`.
 * Neither: no ratio. `met` says whether `target` is met, null when the bound cannot tell.
 */
export function boundedRatio(
  a: { rate: number; limit: boolean },
  b: { rate: number; limit: boolean },
  target: number,
): { ratio: number; kind: 'exact' | 'at least' | 'at most' | 'none'; met: boolean | null } {
  const ratio = a.rate / b.rate;
  if (!Number.isFinite(ratio) || (!a.limit && !b.limit)) return { ratio, kind: 'none', met: null };
  if (a.limit && b.limit) return { ratio, kind: 'exact', met: ratio >= target };
  if (b.limit) return { ratio, kind: 'at least', met: ratio >= target ? true : null };
  return { ratio, kind: 'at most', met: ratio < target ? false : null };
}
