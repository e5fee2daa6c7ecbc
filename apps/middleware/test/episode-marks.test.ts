/** Episode marks: what start, stop and discard do, the lines they store, and what they refuse. */
import { describe, expect, test } from 'vitest';
import {
  decide,
  keptEpisodes,
  marksOf,
  parseEpisodeAction,
  type EpisodeMark,
} from '../src/episodes/marks.ts';

const T = Date.UTC(2026, 10, 27, 8, 0, 0);
const open: EpisodeMark = { startMs: T, stopMs: null, task: 'pick', by: 'ana', discarded: false };

describe('episode actions', () => {
  test('a request body becomes an action, or says what is wrong', () => {
    expect(parseEpisodeAction({ action: 'start', task: ' pick\n the cube ' })).toEqual({
      action: 'start',
      task: 'pick the cube',
    });
    expect(parseEpisodeAction({ action: 'stop' })).toEqual({ action: 'stop' });
    expect(parseEpisodeAction({ action: 'start' })).toEqual({
      error: expect.stringMatching(/needs a task/),
    });
    expect(parseEpisodeAction({ action: 'start', task: 'x'.repeat(501) })).toEqual({
      error: 'task longer than 500 characters',
    });
    expect(parseEpisodeAction(null)).toEqual({ error: expect.stringMatching(/action must be/) });
  });

  test('start stores the task at its start time; a second start is refused while one records', () => {
    const d = decide('arm1', [], { action: 'start', task: 'say "hi"' }, T + 0.7);
    expect(d.status).toBe(201);
    expect(d.lines).toEqual([`episode,arm=arm1 task="say \\"hi\\"" ${T * 1000}`]);
    expect(decide('arm1', [], { action: 'start', task: 'p' }, T, 'ana').lines).toEqual([
      `episode,arm=arm1 task="p",by="ana" ${T * 1000}`,
    ]);
    const again = decide('arm1', [open], { action: 'start', task: 'x' }, T + 5);
    expect(again).toMatchObject({ status: 409, lines: [] });
  });

  test('stop and discard update the open episode at its own time', () => {
    expect(decide('arm1', [open], { action: 'stop' }, T + 3000)).toMatchObject({
      status: 200,
      body: { ok: true, episode: { startMs: T, stopMs: T + 3000, discarded: false } },
      lines: [`episode,arm=arm1 stop=${T + 3000}i ${T * 1000}`],
    });
    expect(decide('arm1', [open], { action: 'discard' }, T + 10).lines).toEqual([
      `episode,arm=arm1 stop=${T + 10}i,discarded=true ${T * 1000}`,
    ]);
    expect(decide('arm1', [], { action: 'stop' }, T)).toMatchObject({
      status: 409,
      body: { errors: ['no episode is recording'] },
    });
  });

  test('stored rows read back as marks; export keeps the stopped, undiscarded ones in range', () => {
    const marks = marksOf([
      { _time: new Date(T + 5000).toISOString(), task: 'b', stop: T + 6000, discarded: true },
      { _time: new Date(T).toISOString(), task: 'a', stop: T + 1000 },
      { _time: new Date(T + 8000).toISOString(), task: 'c' },
    ]);
    expect(marks.map((m) => [m.task, m.stopMs, m.discarded])).toEqual([
      ['a', T + 1000, false],
      ['b', T + 6000, true],
      ['c', null, false],
    ]);
    expect(keptEpisodes(marks).map((m) => m.task)).toEqual(['a']);
    expect(keptEpisodes(marks, T + 1000)).toEqual([]);
  });

  test('cut marks a past range of the history as a stopped episode, under who cut it', () => {
    expect(
      parseEpisodeAction({
        action: 'cut',
        task: 'wave',
        from: new Date(T).toISOString(),
        to: T + 4000,
      }),
    ).toEqual({ action: 'cut', task: 'wave', fromMs: T, toMs: T + 4000 });
    expect(parseEpisodeAction({ action: 'cut', task: 'wave', from: 'now', to: T })).toEqual({
      error: expect.stringMatching(/needs from and to/),
    });
    expect(parseEpisodeAction({ action: 'cut', task: 'wave', from: T, to: T })).toEqual({
      error: 'a cut episode needs from before to',
    });
    expect(parseEpisodeAction({ action: 'cut', from: T, to: T + 1 })).toEqual({
      error: expect.stringMatching(/needs a task/),
    });
    const cut = { action: 'cut', task: 'wave', fromMs: T, toMs: T + 4000 } as const;
    expect(decide('arm1', [open], cut, T + 9000, 'bo')).toMatchObject({
      status: 409,
      body: { errors: [expect.stringMatching(/already starts at/)] },
    });
    const d = decide('arm1', [], cut, T + 9000, 'bo');
    expect(d).toMatchObject({
      status: 201,
      body: { episode: { startMs: T, stopMs: T + 4000, task: 'wave', by: 'bo' } },
      lines: [`episode,arm=arm1 task="wave",by="bo",stop=${T + 4000}i ${T * 1000}`],
    });
    expect(decide('arm1', [], cut, T + 3000)).toMatchObject({ status: 409, lines: [] });
  });

  test('discard with a start throws a stopped episode away; an unknown start is refused', () => {
    const kept = { ...open, stopMs: T + 2000 };
    expect(decide('arm1', [kept], { action: 'discard', startMs: T }, T + 9000)).toMatchObject({
      status: 200,
      body: { episode: { startMs: T, stopMs: T + 2000, discarded: true } },
      lines: [`episode,arm=arm1 stop=${T + 2000}i,discarded=true ${T * 1000}`],
    });
    expect(decide('arm1', [kept], { action: 'discard', startMs: T + 1 }, T + 9000)).toMatchObject({
      status: 409,
      lines: [],
    });
    expect(parseEpisodeAction({ action: 'discard', start: 'x' })).toEqual({
      error: expect.stringMatching(/start is the episode/),
    });
  });
});
