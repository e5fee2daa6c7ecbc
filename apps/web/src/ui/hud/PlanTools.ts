/** The Plan panel's plain objects (built in ../app/createHud.ts, read through `usePlan()`). */
import type { Waypoints } from '../../core/plan/Waypoints.ts';
import type { PlanPreview } from '../../core/plan/PlanPreview.ts';
import type { PlanRunner } from '../../core/plan/PlanRunner.ts';
import type { WaypointEditor } from '../../scene/WaypointEditor.ts';
import type { RunRecorder } from '../../core/plan/RunRecorder.ts';
import type { RunReplay } from '../../core/plan/RunReplay.ts';

export interface PlanTools {
  readonly waypoints: Waypoints;
  /** What the ghost runs along (the 3D view's ghost source). */
  readonly preview: PlanPreview;
  /** Streams a plan to the arm with pose checking. */
  readonly runner: PlanRunner;
  /** The waypoint spheres in 3D (once the 3D view has started). */
  editor: WaypointEditor | null;
  /** Rehearse, then run: the rehearsal in Model mode, the actual run, their tracking error. */
  readonly recorder: RunRecorder;
  /** "Replay run": the actual run as the replay's sibling, the rehearsal as the ghost. */
  readonly runReplay: RunReplay;
}
