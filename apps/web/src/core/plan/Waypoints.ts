/**
 * The plan's waypoints: tip positions in mm (the arm's base frame, z up), in order. Plain
 * mutable state with a version counter: the Plan panel samples it, the 3D editor (spheres,
 * dragging) reads it every frame and writes it while a sphere is dragged. A waypoint taught from
 * history (History → "Make plan from this range") also holds the recorded pose and its timing;
 * moving it by hand makes it a plain tip waypoint.
 */
import type { MotionMode } from '@armtwin/motion';

export interface Waypoint {
  x: number;
  y: number;
  z: number;
  /** Taught: every servo's pulse (µs, profile order; NaN = leave it), reached in joint space. */
  pwm?: number[];
  /** Taught: time from leaving the previous waypoint to reaching this one, ms. */
  durationMs?: number;
  /** Taught: time held here, ms. */
  holdMs?: number;
}

/** At most this many waypoints placed by hand. */
export const MAX_WAYPOINTS = 16;
/** At most this many taught from history (a motion request takes 64 targets). */
export const MAX_TAUGHT_WAYPOINTS = 64;

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
  /** How the plan goes between waypoints: each axis (joint space) or a Cartesian path. */
  mode: MotionMode = 'cartesian';

  setMode(mode: MotionMode): void {
    this.mode = mode;
    this.version++;
  }

  /** Replaces the list with waypoints taught from history, planned in joint space. */
  setTaught(list: readonly Waypoint[]): boolean {
    if (list.length === 0 || list.length > MAX_TAUGHT_WAYPOINTS) return false;
    this.list = list.map((w) => ({ ...w, x: round1(w.x), y: round1(w.y), z: round1(w.z) }));
    this.mode = 'joint';
    this.version++;
    return true;
  }

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
    const next: Waypoint = { x: old.x, y: old.y, z: old.z }; // moved: no longer the taught pose
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
