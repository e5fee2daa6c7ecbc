/**
 * The Cartesian target and its local IK preview, shared by the Cartesian panel (which writes
 * it on user input), the 3D view (target marker, ghost, floor clicks) and the Ghost panel.
 * Plain mutable state plus one listener list for targets placed by a click in the 3D view.
 */
/** Servos a preview can hold (a profile has at most a few dozen). */
const MAX_PREVIEW_SERVOS = 32;

export class TargetPreview {
  /** Whether a target has been entered (the marker and preview ghost are drawn). */
  active = false;
  /** Target tip position, mm. */
  x = 0;
  y = 0;
  z = 0;
  /** Local IK status code of §4 for the target (0 = reachable). */
  code = 0;
  /** Servo angles of the previewed solution, degrees (NaN for servos it leaves be). */
  readonly angles = new Float64Array(MAX_PREVIEW_SERVOS).fill(NaN);
  /**
   * A target refused by a keep-out zone or self-collision: the URDF joint whose child link the
   * ghost paints red, and why ('' when none). The ghost then shows the refused pose.
   */
  hitJoint = '';
  hitMessage = '';
  /** Whether the ghost is drawn at all (the Ghost panel's switch). */
  ghostEnabled = true;
  /**
   * A jog refused by a keep-out zone or self-collision: the pose it would have reached (servo
   * angles, degrees) and the URDF joint whose child link the ghost paints red. Shown until the
   * next jog that is sent, or a Cartesian target.
   */
  refused = false;
  readonly refusedAngles = new Float64Array(MAX_PREVIEW_SERVOS).fill(NaN);
  refusedJoint = '';

  private readonly placeListeners = new Set<(x: number, y: number) => void>();

  set(
    x: number,
    y: number,
    z: number,
    code: number,
    angles: ArrayLike<number>,
    hit?: { joint: string; message: string },
  ): void {
    this.active = true;
    this.refused = false;
    this.hitJoint = hit?.joint ?? '';
    this.hitMessage = hit?.message ?? '';
    this.x = x;
    this.y = y;
    this.z = z;
    this.code = code;
    for (let i = 0; i < MAX_PREVIEW_SERVOS; i++) this.angles[i] = angles[i] ?? NaN;
  }

  /** Shows a refused jog's pose on the ghost, `joint`'s link red. */
  refuse(angles: ArrayLike<number>, joint: string): void {
    this.refused = true;
    this.refusedJoint = joint;
    for (let i = 0; i < MAX_PREVIEW_SERVOS; i++) this.refusedAngles[i] = angles[i] ?? NaN;
  }

  clearRefused(): void {
    this.refused = false;
    this.refusedJoint = '';
  }

  setGhostEnabled(on: boolean): void {
    this.ghostEnabled = on;
  }

  clear(): void {
    this.active = false;
    this.hitJoint = '';
    this.hitMessage = '';
    this.angles.fill(NaN);
  }

  /** A click on the floor at (x, y) mm. */
  place(x: number, y: number): void {
    for (const fn of this.placeListeners) fn(x, y);
  }

  onPlace(fn: (x: number, y: number) => void): () => void {
    this.placeListeners.add(fn);
    return () => this.placeListeners.delete(fn);
  }
}
