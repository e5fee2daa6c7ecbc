/**
 * The motion requests this page sent and the feedback each got, in order (newest first, the
 * last `MAX_REQUESTS`). Plain object fed by FleetLink's feedback; panels sample `version`.
 */
import type { Feedback } from './feedback.ts';

export interface RequestEntry {
  id: string;
  /** What the user asked, as typed. */
  text: string;
  /** Every feedback message for it, in arrival order. */
  feedback: Feedback[];
}

export const MAX_REQUESTS = 5;
/** Feedback kept per request (pauses and re-plans can repeat). */
const MAX_FEEDBACK = 20;

let counter = 0;
/** A request id unique to this page: `hud-<random>-<n>`. */
const PAGE = Math.random().toString(36).slice(2, 8);
export const nextRequestId = (): string => `hud-${PAGE}-${++counter}`;

export class RequestLog {
  entries: RequestEntry[] = [];
  version = 0;

  sent(id: string, text: string): void {
    this.entries = [{ id, text, feedback: [] }, ...this.entries].slice(0, MAX_REQUESTS);
    this.version++;
  }

  /** Feedback for a request of ours (others are ignored). */
  take(f: Feedback): void {
    const e = this.entries.find((x) => x.id === f.id);
    if (!e) return;
    e.feedback = [...e.feedback, f].slice(-MAX_FEEDBACK);
    this.entries = [...this.entries];
    this.version++;
  }
}
