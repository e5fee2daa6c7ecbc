/**
 * What the 3D view reads of the page's objects, declared here so that the objects that feed it
 * (the plan preview, the calibration session, a run's replay, the mode's sibling feed) need
 * nothing of scene/: the view (scene/) imports these, never the other way round.
 */

/** Fills the ghost's servo angles (store degrees) at `now`; false = nothing to show. */
export interface GhostSource {
  sample(now: number, out: Float64Array): boolean;
}

/** What the page reads of the replay (or the model copy) to send the sibling's pose to the 3D view. */
export interface SiblingSource {
  update(now: number): boolean;
  readonly active: boolean;
  /** Shown only while there is one (any non-null value). */
  readonly record: unknown;
  readonly angles: Float64Array;
}
