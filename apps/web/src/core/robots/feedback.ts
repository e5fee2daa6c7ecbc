/**
 * Motion feedback from `arm/{id}/feedback` (docs/protocol.md), read as untrusted input: only
 * the fields the HUD shows, each type-checked, strings cut to a sane length. The HUD renders
 * them as text only. Pure.
 */
import { motionCodeMessage, type MotionStatus } from '@armtwin/motion';

export interface Feedback {
  id: string | null;
  status: MotionStatus;
  code: number;
  message: string;
  event?: string;
  replans?: number;
  servo?: string;
  deviation?: number;
  durationMs?: number;
}

const STATUSES: readonly MotionStatus[] = [
  'planned',
  'unreachable',
  'executing',
  'done',
  'failed',
  'stopped',
];
const MAX_TEXT = 300;
/** Largest feedback message read, bytes. */
export const MAX_FEEDBACK_BYTES = 16384;

const str = (v: unknown): string | undefined =>
  typeof v === 'string' ? v.slice(0, MAX_TEXT) : undefined;
const num = (v: unknown): number | undefined =>
  typeof v === 'number' && Number.isFinite(v) ? v : undefined;

export function parseFeedback(text: string): Feedback | null {
  if (text.length > MAX_FEEDBACK_BYTES) return null;
  let j: unknown;
  try {
    j = JSON.parse(text);
  } catch {
    return null;
  }
  if (typeof j !== 'object' || j === null || Array.isArray(j)) return null;
  const o = j as Record<string, unknown>;
  const status = o.status as MotionStatus;
  if (!STATUSES.includes(status)) return null;
  const f: Feedback = {
    id: str(o.id) ?? null,
    status,
    code: num(o.code) ?? 0,
    message: str(o.message) ?? '',
  };
  const event = str(o.event);
  if (event !== undefined) f.event = event;
  const replans = num(o.replans);
  if (replans !== undefined) f.replans = replans;
  const servo = str(o.servo);
  if (servo !== undefined) f.servo = servo;
  const deviation = num(o.deviation);
  if (deviation !== undefined) f.deviation = deviation;
  const durationMs = num(o.durationMs);
  if (durationMs !== undefined) f.durationMs = durationMs;
  return f;
}

/** One line for a feedback message, e.g. "unreachable: out of reach (code 2)". */
export function feedbackWords(f: Feedback): string {
  switch (f.status) {
    case 'planned':
      return `planned${f.durationMs !== undefined ? `: ${(f.durationMs / 1000).toFixed(1)} s` : ''}`;
    case 'executing':
      if (f.event === 'paused')
        return `paused: servo ${f.servo ?? '?'} off the plan by ${f.deviation?.toFixed(1) ?? '?'}, re-planning`;
      if (f.event === 'replanned') return `executing: re-planned (${f.replans ?? 1})`;
      return 'executing';
    case 'done':
      return 'done';
    case 'unreachable':
      return `unreachable: ${motionCodeMessage(f.code)} (code ${f.code})`;
    case 'failed':
      return `failed (code ${f.code}): ${f.message}`;
    case 'stopped':
      return `stopped: ${f.message || motionCodeMessage(f.code)}`;
  }
}
