/**
 * The Telegraf section's rows (bench/telegraf.ts), per message shape: each consumer's highest
 * zero-loss rate, their ratio (a bound where a ramp ended at the publisher's limit or the list's
 * end), and CPU per 1,000 frames at the highest rate both passed.
 */
import { boundedRatio } from './zero-loss.ts';
import { fmt, type Row } from './types.ts';
import type { Shape } from './telegraf-consumers.ts';
import type { Step } from './telegraf-ramp.ts';

const best = (steps: Step[]) => [...steps].reverse().find((s) => s.passed);

/** The three comparison rows of one message shape. */
export function compareRows(result: Record<string, Step[]>, shape: Shape): Row[] {
  const tg = best(result.Telegraf ?? []);
  const mw = best(result.middleware ?? []);
  // A ramp stopped by the publisher (it could not keep the rate on this machine) or by the end
  // of the list found no limit of that consumer: its figure is a lower bound.
  const atLimit = (all: Step[] | undefined) => {
    const last = all?.at(-1);
    return !(
      !last ||
      last.passed ||
      last.why.startsWith('publisher') ||
      last.why.startsWith('the publisher')
    );
  };
  const r = boundedRatio(
    { rate: mw?.offeredPerS ?? 0, limit: atLimit(result.middleware) },
    { rate: tg?.offeredPerS ?? 0, limit: atLimit(result.Telegraf) },
    3,
  );
  // CPU compared at the highest rate both passed, so both did the same work.
  const common = (result.middleware ?? [])
    .filter(
      (m) => m.passed && result.Telegraf?.some((t) => t.passed && t.offeredPerS === m.offeredPerS),
    )
    .at(-1);
  const tgAt = result.Telegraf?.find((t) => t.offeredPerS === common?.offeredPerS);
  const cpuRatio = common && tgAt ? common.cpuPer1000Ms / tgAt.cpuPer1000Ms : NaN;
  const top = (s: Step | undefined, all: Step[] | undefined) =>
    s
      ? `${s.offeredPerS} frames/s${all?.at(-1)?.passed ? ' (the ramp ended before a failure)' : `; next step failed: ${all?.at(-1)?.why}`}`
      : `none passed (${all?.at(-1)?.why ?? 'not run'})`;
  const what =
    shape === 'frame'
      ? 'one `$TIM`-stamped frame per message (mqtt_consumer + grok → InfluxDB 1.8)'
      : '6-servo groups, one per message (mqtt_consumer + value parser + Starlark split → InfluxDB 1.8)';
  return [
    {
      figure: `Telegraf: highest zero-loss rate, ${what}`,
      value: top(tg, result.Telegraf),
      baseline: `middleware: ${top(mw, result.middleware)}`,
      target: 'reported',
      met: null,
    },
    {
      figure: `middleware ÷ Telegraf, highest zero-loss frames/s, same frames, same run (${shape === 'frame' ? 'single frames' : '6-servo groups'})`,
      value:
        r.kind === 'exact'
          ? `${fmt(r.ratio, 2)}×`
          : r.kind === 'at least'
            ? `≥ ${fmt(r.ratio, 2)}×: Telegraf's ramp ended at its limit, the middleware's at the publisher's or the list's end`
            : r.kind === 'at most'
              ? `≤ ${fmt(r.ratio, 2)}×: the middleware's ramp ended at its limit, Telegraf's at the publisher's or the list's end`
              : `${fmt(r.ratio, 2)}×, not a ratio of limits: both ramps ended at the publisher's limit or the list's end, so both only passed up to there`,
      baseline: 'issue 19: 1.8× (an outside measurement, single frames)',
      target: '≥ 3×',
      met: r.met,
    },
    {
      figure: `CPU per 1,000 frames at the highest rate both passed, middleware ÷ Telegraf (${shape === 'frame' ? 'single frames' : '6-servo groups'})`,
      value: `${fmt(cpuRatio, 2)} (${fmt(common?.cpuPer1000Ms, 1)} vs ${fmt(tgAt?.cpuPer1000Ms, 1)} ms at ${common?.offeredPerS ?? '—'} frames/s)`,
      baseline: 'issue 19: 0.63 (7.6 vs 12.1 ms, single frames)',
      target: '≤ 0.33',
      met: Number.isFinite(cpuRatio) ? cpuRatio <= 1 / 3 : null,
    },
  ];
}
