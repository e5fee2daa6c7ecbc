/**
 * The waypoints in 3D: one numbered sphere each and the path through them, children of the
 * arm's z-up world. Dragging a sphere moves it over the horizontal plane at its height (with
 * Shift held, up and down instead); with "place" on, a click on the floor adds a waypoint.
 * Pointer-downs are taken in the capture phase on the view's container, so the orbit camera and
 * the floor-click target never see a drag that grabbed a sphere (nor, while placing, any click). Runs from the 3D view's one
 * frame loop (`update`): the meshes change only when the waypoints' version does.
 */
import * as THREE from 'three';
import type { SceneView } from './SceneView.ts';
import type { Waypoints } from '../core/plan/Waypoints.ts';

const MM = 0.001;
/** Sphere radius at the default view (0.5 m arm), m; scaled with the camera's distance. */
const RADIUS_M = 0.012;
const DEFAULT_VIEW_DISTANCE_M = 1.37;
const COLOUR = 0xf472b6;
const ACTIVE_COLOUR = 0xfde047;

export class WaypointEditor {
  readonly group = new THREE.Group();
  private readonly geometry = new THREE.SphereGeometry(1, 20, 14);
  private readonly material = new THREE.MeshBasicMaterial({
    color: COLOUR,
    depthTest: false,
    transparent: true,
    opacity: 0.9,
  });
  private readonly activeMaterial = new THREE.MeshBasicMaterial({
    color: ACTIVE_COLOUR,
    depthTest: false,
    transparent: true,
  });
  private readonly path = new THREE.Line(
    new THREE.BufferGeometry(),
    new THREE.LineBasicMaterial({
      color: COLOUR,
      depthTest: false,
      transparent: true,
      opacity: 0.8,
    }),
  );
  private spheres: THREE.Mesh[] = [];
  private version = -1;
  private radius = RADIUS_M;
  private readonly raycaster = new THREE.Raycaster();
  private readonly pointer = new THREE.Vector2();
  private readonly plane = new THREE.Plane();
  private readonly hit = new THREE.Vector3();
  private readonly tmp = new THREE.Vector3();
  private downAt: { x: number; y: number } | null = null;
  private shift = false;

  constructor(
    private readonly viewer: SceneView,
    private readonly waypoints: Waypoints,
  ) {
    this.group.name = 'waypoints';
    this.group.renderOrder = 3;
    this.path.renderOrder = 3;
    this.group.add(this.path);
    viewer.world.add(this.group);
    viewer.frameHooks.add(this.update);
    const el = viewer.canvas.parentElement ?? viewer.canvas;
    el.addEventListener('pointerdown', this.onDown, true);
    el.addEventListener('pointermove', this.onMove, true);
    el.addEventListener('pointerup', this.onUp, true);
  }

  /** Frame hook: rebuilds the spheres and the path when the waypoints changed. */
  readonly update = (): boolean => {
    const cam = this.viewer.camera.position.distanceTo(this.viewer.controls.target);
    const radius = RADIUS_M * Math.max(1, cam / DEFAULT_VIEW_DISTANCE_M);
    if (this.version === this.waypoints.version && Math.abs(radius - this.radius) < 1e-6)
      return false;
    this.version = this.waypoints.version;
    this.radius = radius;
    const list = this.waypoints.list;
    while (this.spheres.length < list.length) {
      const m = new THREE.Mesh(this.geometry, this.material);
      m.renderOrder = 3;
      this.spheres.push(m);
      this.group.add(m);
    }
    while (this.spheres.length > list.length) this.spheres.pop()!.removeFromParent();
    const points: THREE.Vector3[] = [];
    list.forEach((w, i) => {
      const m = this.spheres[i]!;
      m.position.set(w.x * MM, w.y * MM, w.z * MM);
      m.scale.setScalar(radius);
      m.material = i === this.waypoints.dragging ? this.activeMaterial : this.material;
      m.userData.index = i;
      points.push(m.position.clone());
    });
    // A new geometry each time: setFromPoints does not grow an existing position buffer.
    this.path.geometry.dispose();
    this.path.geometry = new THREE.BufferGeometry().setFromPoints(points);
    this.path.visible = points.length > 1;
    return true;
  };

  /** Where waypoint i is on the page, CSS px (for tests), or null. */
  screenPoint(i: number): { x: number; y: number } | null {
    const m = this.spheres[i];
    if (!m) return null;
    m.getWorldPosition(this.tmp).project(this.viewer.camera);
    const r = this.viewer.canvas.getBoundingClientRect();
    return {
      x: r.left + ((this.tmp.x + 1) / 2) * r.width,
      y: r.top + ((1 - this.tmp.y) / 2) * r.height,
    };
  }

  private ray(e: PointerEvent): THREE.Ray {
    const r = this.viewer.canvas.getBoundingClientRect();
    this.pointer.set(
      ((e.clientX - r.left) / r.width) * 2 - 1,
      -((e.clientY - r.top) / r.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(this.pointer, this.viewer.camera);
    return this.raycaster.ray;
  }

  private readonly onDown = (e: PointerEvent): void => {
    if (e.button !== 0 || e.target !== this.viewer.canvas) return;
    this.ray(e);
    const hits = this.raycaster.intersectObjects(this.spheres, false);
    if (hits.length === 0) {
      // Placing: the click is ours (no orbiting, no Cartesian target) until the switch is off.
      this.downAt = this.waypoints.placing ? { x: e.clientX, y: e.clientY } : null;
      if (this.downAt) e.stopPropagation();
      return;
    }
    e.stopPropagation();
    const i = hits[0]!.object.userData.index as number;
    this.waypoints.dragging = i;
    this.waypoints.version++;
    this.shift = e.shiftKey;
    this.setPlane(hits[0]!.object.getWorldPosition(this.tmp), e.shiftKey);
    this.viewer.controls.enabled = false;
    this.viewer.canvas.setPointerCapture?.(e.pointerId);
  };

  /** The drag plane through `at` (three's world): horizontal, or vertical facing the camera. */
  private setPlane(at: THREE.Vector3, vertical: boolean): void {
    if (!vertical) {
      this.plane.setFromNormalAndCoplanarPoint(new THREE.Vector3(0, 1, 0), at);
      return;
    }
    const n = this.viewer.camera.position.clone().sub(at);
    n.y = 0;
    if (n.lengthSq() < 1e-9) n.set(0, 0, 1);
    this.plane.setFromNormalAndCoplanarPoint(n.normalize(), at);
  }

  private readonly onMove = (e: PointerEvent): void => {
    const i = this.waypoints.dragging;
    if (i < 0) return;
    e.stopPropagation();
    if (!this.ray(e).intersectPlane(this.plane, this.hit)) return;
    this.viewer.world.worldToLocal(this.hit);
    const w = this.waypoints.list[i];
    if (!w) return;
    if (this.shift) this.waypoints.move(i, { z: Math.max(0, this.hit.z / MM) });
    else this.waypoints.move(i, { x: this.hit.x / MM, y: this.hit.y / MM });
  };

  private readonly onUp = (e: PointerEvent): void => {
    if (this.waypoints.dragging >= 0) {
      this.waypoints.dragging = -1;
      this.waypoints.version++;
      this.viewer.controls.enabled = true;
      return;
    }
    const d = this.downAt;
    this.downAt = null;
    if (!d || !this.waypoints.placing || Math.hypot(e.clientX - d.x, e.clientY - d.y) > 4) return;
    this.plane.set(new THREE.Vector3(0, 1, 0), 0);
    if (!this.ray(e).intersectPlane(this.plane, this.hit)) return;
    this.viewer.world.worldToLocal(this.hit);
    this.waypoints.add({ x: this.hit.x / MM, y: this.hit.y / MM, z: this.waypoints.placeZ });
  };
}
