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

function keep<T, A>(
  view: Loaded<A>,
  items: (a: A) => T[],
  set: (a: A, kept: T[]) => A,
  ok: (t: T) => boolean,
): Loaded<A> {
  if (!view.ok) return view;
  return { ok: true, data: set(view.data, items(view.data).filter(ok)) };
}

export function onlyProfileServos(o: OverviewViews, ids: readonly string[]): ProfileOverview {
  const mine = new Set(ids);
  const others = new Set<string>();
  const ours = (x: { id: string }) => mine.has(x.id) || (others.add(x.id), false);
  const overview: OverviewViews = {
    range: o.range,
    temp: keep(
      o.temp,
      (a) => a.series,
      (a, series) => ({ ...a, series }),
      ours,
    ),
    volt: keep(
      o.volt,
      (a) => a.series,
      (a, series) => ({ ...a, series }),
      ours,
    ),
    tracking: keep(
      o.tracking,
      (a) => a.joints,
      (a, joints) => ({ ...a, joints }),
      ours,
    ),
    alarms: keep(
      o.alarms,
      (a) => a.episodes,
      (a, episodes) => ({ ...a, episodes }),
      ours,
    ),
    audit: o.audit, // who did what: the arm's, not a servo's
    thermal: keep(
      o.thermal,
      (a) => a.servos,
      (a, servos) => ({ ...a, servos }),
      ours,
    ),
  };
  return { overview, others: [...others].sort() };
}
