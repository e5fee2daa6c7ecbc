import type { ConnectionState } from '../../../core/store/ArmStore.ts';

export const CONNECTION_WORDS: Record<ConnectionState, string> = {
  idle: 'not connected',
  connecting: 'connecting…',
  connected: 'connected',
  reconnecting: 'reconnecting…',
  offline: 'disconnected',
  error: 'connection error',
};

export const armWords = (online: boolean | null): string =>
  online === true ? 'online' : online === false ? 'offline' : 'unknown (no online message)';

export const formatRate = (perS: number): string =>
  perS >= 100 ? perS.toFixed(0) : perS.toFixed(1);

/** `1 bad profile, 2 bad summaries, 2 bad feedback` ('' when none). */
export function fleetRejects(c: {
  badProfiles: number;
  badSummaries: number;
  badAlerts: number;
  badFeedback: number;
}): string {
  const parts: string[] = [];
  if (c.badProfiles > 0)
    parts.push(`${c.badProfiles} bad profile${c.badProfiles === 1 ? '' : 's'}`);
  if (c.badSummaries > 0)
    parts.push(`${c.badSummaries} bad summar${c.badSummaries === 1 ? 'y' : 'ies'}`);
  if (c.badAlerts > 0) parts.push(`${c.badAlerts} bad alert${c.badAlerts === 1 ? '' : 's'}`);
  if (c.badFeedback > 0) parts.push(`${c.badFeedback} bad feedback`);
  return parts.join(', ');
}

/** `2 rejected (bad-url 1, bad-label 1)` ('' when none), from CameraHub's counts by reason. */
export function cameraRejects(total: number, byReason: Record<string, number>): string {
  if (total === 0) return '';
  const parts = Object.entries(byReason)
    .filter(([, n]) => n > 0)
    .map(([k, n]) => `${k} ${n}`);
  return `${total} rejected (${parts.join(', ')})`;
}

/**
 * Where the 3D view is drawn, and how: `Rendering: worker, software WebGL paced to 50 % (18 ms a
 * frame)`; a fallback's reason in brackets after the thread.
 */
export function renderWords(r: {
  thread: 'main' | 'worker';
  note: string;
  software: boolean;
  frameCostMs: number;
  budget: number;
}): string {
  const where = r.thread === 'worker' ? 'Rendering: worker' : 'Rendering: main thread';
  const w = r.note ? `${where} (${r.note})` : where;
  if (!r.software) return w;
  return r.frameCostMs > 0
    ? `${w}, software WebGL paced to ${Math.round(r.budget * 100)} % (${Math.round(r.frameCostMs)} ms a frame)`
    : `${w}, software WebGL`;
}

/** What the 3D arm shows: a prediction (and how far ahead of the reports), or the reports. */
export function twinWords(mode: string, predicting: boolean, leadMs: number): string {
  if (predicting) return `Predicted: drawn ${leadMs} ms ahead of the arm's last report.`;
  if (mode === 'interpolate') return 'Interpolated between the arm’s reports.';
  return 'Drawn as the arm reports.';
}
