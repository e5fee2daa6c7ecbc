/**
 * What the page's other parts use of the 3D view, wherever its runtime draws (the render worker
 * or the main thread), through the page side of the runtime (./render/SceneClient.ts), or the
 * view that falls back from one to the other (./render/FallbackSceneView.ts). The scene graph, camera, orbit controls and canvas here are the
 * page's: picking and dragging (FloorPicker, the Plan panel's WaypointEditor) raycast them.
 */
import type * as THREE from 'three';
import type { URDFRobot } from 'urdf-loader';
import type { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import type { ProfileKeepOut } from '@armtwin/robot';
import type { JointMap } from '../core/robots/robotSpec.ts';
import type { GhostSource } from './sceneHooks.ts';
import type { MeshFailure } from './loadRobot.ts';
import type { RenderThread } from '../core/config/renderThread.ts';
import type { ReadonlySceneReports } from './render/SceneReports.ts';

/** Which of the drawn robots: the live arm, the ghost, the replay's sibling. */
export type DrawnRobot = 'robot' | 'ghost' | 'sibling';

export type { RenderThread };

export interface SceneView {
  readonly thread: RenderThread;
  readonly scene: THREE.Scene;
  readonly camera: THREE.PerspectiveCamera;
  readonly controls: OrbitControls;
  /** The arm's z-up frame (metres). */
  readonly world: THREE.Group;
  readonly canvas: HTMLCanvasElement;
  readonly liveRobot: URDFRobot | null;
  readonly zones: { readonly names: string[] };
  readonly ghostPainted: string;
  readonly meshFailures: readonly MeshFailure[];
  readonly pixelRatio: number;
  /** A moving frame's cost, ms, where frames run on a budget (software WebGL in the worker); else 0. */
  readonly frameCostMs: number;
  readonly software: boolean;
  readonly renderedFrames: number;
  /** What the runtime said of its last drawn frame (read-only: nothing feeds it to the store). */
  readonly reports: ReadonlySceneReports;
  ghostSource: GhostSource | null;
  /** Called every frame; a hook returning true asks for a render. */
  readonly frameHooks: Set<(now: number) => boolean>;
  /** Called after each rendered frame with its `performance.now()` (bench probe, tests). */
  readonly renderHooks: Set<(now: number) => void>;
  jointValues(which?: DrawnRobot): number[];
  showZones(keepOut: ProfileKeepOut | undefined): void;
  load(urdfUrl: string, joints: JointMap): Promise<void>;
  start(): void;
  invalidate(): void;
  dispose(): void;
}
