/** `/history/audit?format=csv`: the control events as one CSV table. Pure. */
import type { AuditRecord } from '@armtwin/api';

export const AUDIT_CSV_HEADER = 'time,by,kind,detail';

/** A CSV cell: quoted when it holds a comma, a quote or a line break (RFC 4180). */
const cell = (s: string): string => (/[",\r\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s);

export function auditCsv(events: readonly AuditRecord[]): string {
  const rows = events.map(
    (e) => `${new Date(e.at).toISOString()},${cell(e.by)},${cell(e.kind)},${cell(e.detail)}`,
  );
  return [AUDIT_CSV_HEADER, ...rows].join('\n') + '\n';
}
