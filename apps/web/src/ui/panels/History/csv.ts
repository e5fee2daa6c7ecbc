/**
 * CSV export of what the History panel shows, built in the browser (RFC 4180: comma, CRLF,
 * quotes doubled). One file per view: a chart's aligned series (one column per line), the
 * tracking-error table, the alarm log. Times as epoch ms and ISO 8601 UTC. Pure.
 */
import type { Aligned } from './align.ts';
import type { AlarmEpisode, TrackingJoint, AuditRecord } from '@armtwin/api';

export type Cell = string | number | null | undefined;

/**
 * One cell. Numbers as they are; text quoted when it holds `,` `"` CR or LF, and prefixed
 * with `'` when it starts like a spreadsheet formula (= + - @), so opening the file runs nothing.
 */
export function csvCell(v: Cell): string {
  if (v === null || v === undefined) return '';
  if (typeof v === 'number') return Number.isFinite(v) ? String(v) : '';
  let s = /^[=+\-@\t\r]/.test(v) ? `'${v}` : v;
  if (/[",\r\n]/.test(s)) s = `"${s.replace(/"/g, '""')}"`;
  return s;
}

export function toCsv(header: readonly string[], rows: readonly (readonly Cell[])[]): string {
  return [header, ...rows].map((r) => r.map(csvCell).join(',')).join('\r\n') + '\r\n';
}

const iso = (ms: number | null) => (ms === null ? null : new Date(ms).toISOString());

/** `time_ms,time_utc,<label>…`, one row per time on the shared axis. */
export function seriesCsv(a: Aligned): string {
  return toCsv(
    ['time_ms', 'time_utc', ...a.labels],
    a.times.map((t, i) => [t, iso(t), ...a.columns.map((c) => c[i])]),
  );
}

export function trackingCsv(
  joints: readonly TrackingJoint[],
  name: (id: string) => string,
): string {
  return toCsv(
    ['id', 'joint', 'samples', 'mean_abs_error_deg', 'max_abs_error_deg', 'max_at_utc'],
    joints.map((j) => [j.id, name(j.id), j.samples, j.meanAbsError, j.maxAbsError, iso(j.maxAt)]),
  );
}

export function alarmsCsv(episodes: readonly AlarmEpisode[], name: (id: string) => string): string {
  return toCsv(
    ['kind', 'id', 'servo', 'start_utc', 'end_utc', 'ongoing', 'peak'],
    episodes.map((e) => [
      e.kind,
      e.id,
      name(e.id),
      iso(e.start),
      iso(e.end),
      e.end === null ? 'yes' : 'no',
      e.peak,
    ]),
  );
}

/** The control log: one row per event. */
export function auditCsv(events: readonly AuditRecord[]): string {
  return toCsv(
    ['time_utc', 'by', 'kind', 'detail'],
    events.map((e) => [iso(e.at), e.by, e.kind, e.detail]),
  );
}

/** `armtwin-<arm>-<view>-<start>.csv` with a filesystem-safe timestamp. */
export function csvFileName(arm: string, view: string, start: number): string {
  const stamp = new Date(start).toISOString().slice(0, 19).replace(/[:]/g, '');
  return `armtwin-${arm}-${view}-${stamp}Z.csv`.replace(/[^A-Za-z0-9._-]/g, '_');
}
