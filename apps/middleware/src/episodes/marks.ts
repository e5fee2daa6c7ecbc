/**
 * Episodes: marked time ranges of an arm's history with a task text (LeRobot's `single_task`),
 * which `armtwin export --format lerobot --episodes` cuts out as a dataset. An operator starts
 * one (`start` with the task), stops it, or discards it; at most one is open (recording) per
 * arm. An episode can also be cut afterwards from a range of the history (`cut`, with `from`
 * and `to`), and a stopped one discarded by its start (`discard` with `start`). Stored as one
 * `episode` point per episode at its start (PROTOCOL.md §6), fields merged as it changes:
 * `task`, `by` (who marked it), `stop` (epoch ms), `discarded`. Pure: the store (./store.ts)
 * reads the marks and writes the lines this decides.
 */
import type { EpisodeMark } from '@armtwin/api';
import { episodeLine } from '../points.ts';

export type { EpisodeMark };

export const MAX_TASK_LENGTH = 500;

export type EpisodeAction =
  | { action: 'start'; task: string }
  | { action: 'stop' }
  /** The recording one, or (with `startMs`) a stopped one. */
  | { action: 'discard'; startMs?: number }
  | { action: 'cut'; task: string; fromMs: number; toMs: number };

/** An ISO 8601 time or epoch ms as epoch ms, or null. */
function timeOf(v: unknown): number | null {
  if (typeof v === 'number') return Number.isFinite(v) ? Math.floor(v) : null;
  if (typeof v !== 'string' || !/^\d{4}-\d\d-\d\d/.test(v)) return null;
  const ms = Date.parse(v);
  return Number.isFinite(ms) ? ms : null;
}

function taskOf(v: unknown, what: string): string | { error: string } {
  const task = typeof v === 'string' ? v.replace(/\s+/g, ' ').trim() : '';
  if (!task) return { error: `${what} needs a task: one line saying what is done` };
  if (task.length > MAX_TASK_LENGTH)
    return { error: `task longer than ${MAX_TASK_LENGTH} characters` };
  return task;
}

/** A request body as an action, or the reason it is not one. */
export function parseEpisodeAction(body: unknown): EpisodeAction | { error: string } {
  const b = (body ?? {}) as Record<string, unknown>;
  if (b.action === 'stop') return { action: 'stop' };
  if (b.action === 'discard') {
    if (b.start === undefined) return { action: 'discard' };
    const startMs = timeOf(b.start);
    if (startMs === null) return { error: 'start is the episode to discard: its start time' };
    return { action: 'discard', startMs };
  }
  if (b.action === 'cut') {
    const task = taskOf(b.task, 'a cut episode');
    if (typeof task !== 'string') return task;
    const [fromMs, toMs] = [timeOf(b.from), timeOf(b.to)];
    if (fromMs === null || toMs === null)
      return { error: 'a cut episode needs from and to (ISO 8601 times or epoch ms)' };
    if (toMs <= fromMs) return { error: 'a cut episode needs from before to' };
    return { action: 'cut', task, fromMs, toMs };
  }
  if (b.action !== 'start')
    return {
      error: 'action must be "start" (with a task), "stop", "discard" or "cut" (task, from, to)',
    };
  const task = taskOf(b.task, 'a started episode');
  return typeof task === 'string' ? { action: 'start', task } : task;
}

/** Stored rows (`_time`, `task`, `stop`, `discarded`) as marks, in start order. */
export function marksOf(rows: readonly Record<string, unknown>[]): EpisodeMark[] {
  return rows
    .map((r) => ({
      startMs: Math.floor(Date.parse(String(r._time))),
      stopMs: typeof r.stop === 'number' ? r.stop : null,
      task: typeof r.task === 'string' ? r.task : '',
      by: typeof r.by === 'string' ? r.by : '',
      discarded: r.discarded === true,
    }))
    .filter((m) => Number.isFinite(m.startMs))
    .sort((a, b) => a.startMs - b.startMs);
}

export const isOpen = (m: EpisodeMark) => m.stopMs === null && !m.discarded;

export interface Decision {
  status: 200 | 201 | 409;
  body: { ok: true; episode: EpisodeMark } | { ok: false; errors: string[] };
  /** Lines to store (none for a refusal). */
  lines: string[];
}

/** What `action` by `by` at `nowMs` does to an arm whose marks are `marks`. */
export function decide(
  arm: string,
  marks: readonly EpisodeMark[],
  action: EpisodeAction,
  nowMs: number,
  by = '',
): Decision {
  const open = marks.find(isOpen);
  const refuse = (error: string): Decision => ({
    status: 409,
    body: { ok: false, errors: [error] },
    lines: [],
  });
  if (action.action === 'start') {
    if (open)
      return refuse(
        `an episode is recording since ${new Date(open.startMs).toISOString()}: stop or discard it first`,
      );
    const last = marks.at(-1);
    const startMs = Math.max(Math.floor(nowMs), last ? last.startMs + 1 : 0);
    const episode = { startMs, stopMs: null, task: action.task, by, discarded: false };
    return {
      status: 201,
      body: { ok: true, episode },
      lines: [episodeLine(arm, { task: action.task, by }, startMs * 1000)],
    };
  }
  if (action.action === 'cut') {
    const { fromMs, toMs, task } = action;
    if (toMs > nowMs)
      return refuse('a cut episode ends by now: the history after it is not there yet');
    if (marks.some((m) => m.startMs === fromMs))
      return refuse(`an episode already starts at ${new Date(fromMs).toISOString()}`);
    const episode = { startMs: fromMs, stopMs: toMs, task, by, discarded: false };
    return {
      status: 201,
      body: { ok: true, episode },
      lines: [episodeLine(arm, { task, by, stop: toMs }, fromMs * 1000)],
    };
  }
  if (action.action === 'discard' && action.startMs !== undefined) {
    const m = marks.find((x) => x.startMs === action.startMs && !x.discarded);
    if (!m) return refuse(`no kept episode starts at ${new Date(action.startMs).toISOString()}`);
    const stopMs = m.stopMs ?? Math.max(Math.floor(nowMs), m.startMs + 1);
    return {
      status: 200,
      body: { ok: true, episode: { ...m, stopMs, discarded: true } },
      lines: [episodeLine(arm, { stop: stopMs, discarded: true }, m.startMs * 1000)],
    };
  }
  if (!open) return refuse('no episode is recording');
  const stopMs = Math.max(Math.floor(nowMs), open.startMs + 1);
  const discarded = action.action === 'discard';
  const episode = { ...open, stopMs, discarded };
  const fields = discarded ? { stop: stopMs, discarded: true as const } : { stop: stopMs };
  return {
    status: 200,
    body: { ok: true, episode },
    lines: [episodeLine(arm, fields, open.startMs * 1000)],
  };
}

/** The kept (stopped, not discarded) episodes overlapping [fromMs, toMs). */
export const keptEpisodes = (marks: readonly EpisodeMark[], fromMs = -Infinity, toMs = Infinity) =>
  marks.filter((m) => !m.discarded && m.stopMs !== null && m.stopMs > fromMs && m.startMs < toMs);
