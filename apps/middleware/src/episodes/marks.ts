/**
 * Episodes: marked time ranges of an arm's history with a task text (LeRobot's `single_task`),
 * which `armtwin export --format lerobot --episodes` cuts out as a dataset. An operator starts
 * one (`start` with the task), stops it, or discards it; at most one is open (recording) per
 * arm. Stored as one `episode` point per episode at its start (PROTOCOL.md §6), fields merged
 * as it changes: `task`, `stop` (epoch ms), `discarded`. Pure: the store (./store.ts) reads the
 * marks and writes the lines this decides.
 */
import { episodeLine } from '../points.ts';

export const MAX_TASK_LENGTH = 500;

export interface EpisodeMark {
  /** Epoch ms; also the episode's id. */
  startMs: number;
  /** Epoch ms; null while it records. */
  stopMs: number | null;
  task: string;
  discarded: boolean;
}

export type EpisodeAction = { action: 'start'; task: string } | { action: 'stop' | 'discard' };

/** A request body as an action, or the reason it is not one. */
export function parseEpisodeAction(body: unknown): EpisodeAction | { error: string } {
  const b = (body ?? {}) as { action?: unknown; task?: unknown };
  if (b.action === 'stop' || b.action === 'discard') return { action: b.action };
  if (b.action !== 'start')
    return { error: 'action must be "start" (with a task), "stop" or "discard"' };
  const task = typeof b.task === 'string' ? b.task.replace(/\s+/g, ' ').trim() : '';
  if (!task) return { error: 'a started episode needs a task: one line saying what is done' };
  if (task.length > MAX_TASK_LENGTH)
    return { error: `task longer than ${MAX_TASK_LENGTH} characters` };
  return { action: 'start', task };
}

/** Stored rows (`_time`, `task`, `stop`, `discarded`) as marks, in start order. */
export function marksOf(rows: readonly Record<string, unknown>[]): EpisodeMark[] {
  return rows
    .map((r) => ({
      startMs: Math.floor(Date.parse(String(r._time))),
      stopMs: typeof r.stop === 'number' ? r.stop : null,
      task: typeof r.task === 'string' ? r.task : '',
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

/** What `action` at `nowMs` does to an arm whose marks are `marks`. */
export function decide(
  arm: string,
  marks: readonly EpisodeMark[],
  action: EpisodeAction,
  nowMs: number,
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
    const episode = { startMs, stopMs: null, task: action.task, discarded: false };
    return {
      status: 201,
      body: { ok: true, episode },
      lines: [episodeLine(arm, { task: action.task }, startMs * 1000)],
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
