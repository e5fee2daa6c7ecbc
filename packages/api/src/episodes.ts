/**
 * `/arms/{id}/episodes` (docs/dataset.md): an arm's episodes, marked time ranges of its history
 * with a task, as the middleware answers them and the HUD's History panel lists them.
 */

export interface EpisodeMark {
  /** Epoch ms; also the episode's id. */
  startMs: number;
  /** Epoch ms; null while it records. */
  stopMs: number | null;
  /** One line: what is done (LeRobot's `single_task`). */
  task: string;
  /** Who marked it (a user's name, `token`, `anonymous`; '' when stored before it was kept). */
  by: string;
  discarded: boolean;
}

/** `GET`: every mark in the range, in start order, discarded ones included. */
export interface EpisodesAnswer {
  ok: true;
  episodes: EpisodeMark[];
}

/** `POST`: the mark as it is now, or why not (`errors`). */
export type EpisodeActionAnswer =
  { ok: true; episode: EpisodeMark; note?: string } | { ok: false; errors: string[] };
