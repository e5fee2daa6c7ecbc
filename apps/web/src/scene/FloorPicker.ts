/**
 * A click (not a drag) on the floor of the 3D view places the Cartesian target there
 * (`TargetPreview.place`, in mm of the arm's frame). Pointer events on the canvas only.
 */
import * as THREE from 'three';
import type { TargetPreview } from '../core/store/TargetPreview.ts';
import type { Stage } from './stage.ts';

const MM = 0.001;
/** A pointer that moved further than this between down and up was a drag, px. */
const CLICK_SLOP_PX = 4;

export class FloorPicker {
  private readonly raycaster = new THREE.Raycaster();
  private readonly pointer = new THREE.Vector2();
  private readonly hit = new THREE.Vector3();
  private downAt: { x: number; y: number } | null = null;

  constructor(
    private readonly canvas: HTMLCanvasElement,
    private readonly camera: THREE.Camera,
    private readonly stage: Stage,
    private readonly target: TargetPreview,
  ) {}

  attach(): void {
    this.canvas.addEventListener('pointerdown', this.onPointerDown);
    this.canvas.addEventListener('pointerup', this.onPointerUp);
  }

  detach(): void {
    this.canvas.removeEventListener('pointerdown', this.onPointerDown);
    this.canvas.removeEventListener('pointerup', this.onPointerUp);
  }

  private readonly onPointerDown = (e: PointerEvent): void => {
    this.downAt = e.button === 0 ? { x: e.clientX, y: e.clientY } : null;
  };

  private readonly onPointerUp = (e: PointerEvent): void => {
    const d = this.downAt;
    this.downAt = null;
    if (!d || Math.hypot(e.clientX - d.x, e.clientY - d.y) > CLICK_SLOP_PX) return;
    const rect = this.canvas.getBoundingClientRect();
    this.pointer.set(
      ((e.clientX - rect.left) / rect.width) * 2 - 1,
      -((e.clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(this.pointer, this.camera);
    if (!this.raycaster.ray.intersectPlane(this.stage.floorPlane, this.hit)) return;
    this.stage.world.worldToLocal(this.hit); // three's y-up → the arm's z-up frame, metres
    this.target.place(Math.round(this.hit.x / MM), Math.round(this.hit.y / MM));
  };
}
