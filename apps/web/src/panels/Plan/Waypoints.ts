/**
 * The plan's waypoints: tip positions in mm (the arm's base frame, z up), in order. Plain
 * mutable state with a version counter: the Plan panel samples it, the 3D editor (spheres,
 * dragging) reads it every frame and writes it while a sphere is dragged.
 */
export interface Waypoint {
  x: number;
  y: number;
  z: number;
}

/** At most this many waypoints (a motion request takes 64 targets). */
export const MAX_WAYPOINTS = 16;

export class Waypoints {
  list: Waypoint[] = [];
  /** Bumped on every change. */
  version = 0;
  /** Index of the sphere being dragged, −1 = none. */
  dragging = -1;
  /** Whether a click on the floor adds a waypoint (the Plan panel's switch). */
  placing = false;
  /** Height (mm) a waypoint placed on the floor gets. */
  placeZ = 150;

  setPlacing(on: boolean): void {
    this.placing = on;
    this.version++;
  }

  add(w: Waypoint): boolean {
    if (this.list.length >= MAX_WAYPOINTS || ![w.x, w.y, w.z].every(Number.isFinite)) return false;
    this.list = [...this.list, { x: round1(w.x), y: round1(w.y), z: round1(w.z) }];
    this.version++;
    return true;
  }

  move(i: number, w: Partial<Waypoint>): void {
    const old = this.list[i];
    if (!old) return;
    const next = { ...old };
    for (const k of ['x', 'y', 'z'] as const) {
      const v = w[k];
      if (v !== undefined && Number.isFinite(v)) next[k] = round1(v);
    }
    this.list = this.list.map((p, j) => (j === i ? next : p));
    this.version++;
  }

  remove(i: number): void {
    if (i < 0 || i >= this.list.length) return;
    this.list = this.list.filter((_, j) => j !== i);
    this.version++;
  }

  clear(): void {
    this.list = [];
    this.version++;
  }
}

const round1 = (v: number) => Math.round(v * 10) / 10;
