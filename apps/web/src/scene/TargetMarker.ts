/**
 * The Cartesian target in 3D: the stage's marker (a sphere and a stem to the floor) follows the
 * target the page last sent (`SceneFrame.target`, ./render/SceneFrame.ts), green when the local IK reaches it, red when not. Checked every frame by the
 * 3D view's loop; the marker changes only when the target does.
 */
import type { SceneFrame } from './render/SceneFrame.ts';
import type { Stage } from './stage.ts';

const MM = 0.001;

export class TargetMarker {
  constructor(
    private readonly stage: Stage,
    private readonly frame: Pick<SceneFrame, 'target'>,
  ) {}

  /** True when the marker moved, changed colour, appeared or disappeared. */
  update(): boolean {
    const t = this.frame.target;
    const m = this.stage.marker;
    let changed = false;
    if (m.visible !== t.active) {
      m.visible = t.active;
      changed = true;
    }
    if (!t.active) return changed;
    const x = t.x * MM;
    const y = t.y * MM;
    const z = t.z * MM;
    const ok = t.code === 0;
    if (
      m.position.x !== x ||
      m.position.y !== y ||
      m.position.z !== z ||
      this.stage.markerOk !== ok
    ) {
      this.stage.placeMarker(x, y, z, ok);
      changed = true;
    }
    return changed;
  }
}
