/**
 * The History panel shows the servos of the arm's current profile only. InfluxDB keeps what an
 * arm id ever sent: after a profile change under the same id (a 7-axis robot simulated as
 * `arm1` yesterday, the 5-axis one today) the range may hold series of servos the arm no longer
 * has. They are left out of the charts, the tracking table and the alarm log, and named
 * (`others`) so the page can say so. Pure.
 */
import type { Loaded } from './loaded.ts';
import type { OverviewViews } from './loadHistory.ts';

export interface ProfileOverview {
  overview: OverviewViews;
  /** Servo ids (three digits, ascending) with data in the range but not in the profile. */
  others: string[];
}

/** `view` with only the items of its list `key` that pass `ok`. */
function keep<K extends string, A extends Record<K, readonly { id: string }[]>>(
  view: Loaded<A>,
  key: K,
  ok: (item: { id: string }) => boolean,
): Loaded<A> {
  if (!view.ok) return view;
  return { ok: true, data: { ...view.data, [key]: view.data[key].filter(ok) } };
}

export function onlyProfileServos(o: OverviewViews, ids: readonly string[]): ProfileOverview {
  const mine = new Set(ids);
  const others = new Set<string>();
  const ours = (x: { id: string }) => mine.has(x.id) || (others.add(x.id), false);
  const overview: OverviewViews = {
    range: o.range,
    temp: keep(o.temp, 'series', ours),
    volt: keep(o.volt, 'series', ours),
    tracking: keep(o.tracking, 'joints', ours),
    alarms: keep(o.alarms, 'episodes', ours),
    audit: o.audit, // who did what: the arm's, not a servo's
    thermal: keep(o.thermal, 'servos', ours),
  };
  return { overview, others: [...others].sort() };
}
