/**
 * The messages between the page (./SceneClient.ts) and the scene runtime's host (./sceneHost.ts),
 * in the render worker or on the main thread. The page keeps MQTT, the store, the panels, the
 * orbit camera and picking; the runtime draws. Everything here is
 * structured-clone data: plain numbers, strings, arrays and typed arrays, no three.js objects.
 */
import type { ProfileKeepOut } from '@armtwin/robot';
import type { PoseCourseInput } from './PoseCourse.ts';
import type { JointMap } from '../../core/robots/robotSpec.ts';
import type { MeshFailure } from '../loadRobot.ts';
import type { TrackingErrors } from '../../core/store/trackingError.ts';
import type { SceneFrame } from './SceneFrame.ts';

/** The orbit camera as the page holds it (three's y-up scene coordinates). */
export interface CameraState {
  position: [number, number, number];
  quaternion: [number, number, number, number];
  fov: number;
  near: number;
  far: number;
}

/** The Cartesian target and ghost switches, copied from the page's TargetPreview. */
export interface TargetState {
  active: boolean;
  x: number;
  y: number;
  z: number;
  code: number;
  angles: Float64Array;
  hitJoint: string;
  ghostEnabled: boolean;
  refused: boolean;
  refusedAngles: Float64Array;
  refusedJoint: string;
}

/** What ../TrackingPaint.ts reads of the store's TrackingErrors. */
export interface TrackingState {
  active: boolean;
  version: number;
  colours: Int32Array;
  levels: TrackingErrors['levels'];
}

/**
 * What the page sends each frame something changed (undefined: unchanged): the parts of the
 * runtime's snapshot (./SceneFrame.ts) that changed, the sampled pose, the camera and paint.
 */
export interface FrameInput extends Partial<
  Pick<SceneFrame, 'arm' | 'commandedPwm' | 'target' | 'plan' | 'sibling'>
> {
  type: 'frame';
  /** The live arm's drawn servo angles, degrees (the store's `rendered`). */
  rendered?: Float64Array;
  /**
   * With `rendered`, for the predictive twin: the instant it is for and the predicted poses
   * after it, so the worker draws the pose of its own frame's instant (./PoseCourse.ts).
   */
  course?: PoseCourseInput;
  camera?: CameraState;
  /** The live arm's tracking-error paint (store/trackingError.ts), when it changed. */
  tracking?: TrackingState;
  /** Draw again even if nothing above changed (a settings change). */
  invalidate?: boolean;
}

export type ToWorker =
  | {
      type: 'init';
      /** The worker's canvas (transferred); absent where the host was given the page's own. */
      canvas?: OffscreenCanvas;
      width: number;
      height: number;
      dpr: number;
      /** Pace software WebGL's frames (../FramePacer.ts `SOFTWARE_PACING`). */
      pace: boolean;
    }
  /** `seq` counts the page's resizes: each drawn frame says which size it was drawn at. */
  | { type: 'resize'; width: number; height: number; dpr: number; seq: number }
  | { type: 'load'; id: number; urdfUrl: string; joints: JointMap; sibling: boolean }
  | { type: 'zones'; keepOut: ProfileKeepOut | undefined }
  /**
   * What the page's other parts added to the arm's world (the Plan panel's waypoint spheres and
   * path), as three's JSON (`Object3D.toJSON`): replaces the copies drawn before.
   */
  | {
      type: 'extras';
      /** Added to the arm's z-up world (waypoints, the cameras' screens). */
      objects: unknown[];
      /** Added to the scene itself (a camera's picture behind everything while viewing through). */
      sceneObjects: unknown[];
      /** Indexes of the stage's own scene children hidden now (the floor while viewing through). */
      hidden: number[];
    }
  /**
   * A new picture for the texture of the mesh `uuid` (sent in `extras` without it): a camera's
   * frame, at most `TEXTURE_HZ` a second per camera (../CameraScreens.ts).
   */
  | { type: 'texture'; uuid: string; bitmap: ImageBitmap }
  | FrameInput;

/** Where the worker framed the camera for a new robot: the page's orbit camera takes it. */
export interface FramedCamera {
  position: [number, number, number];
  target: [number, number, number];
  far: number;
  maxDistance: number;
}

export type FromWorker =
  | { type: 'ready'; software: boolean; renderer: string }
  | {
      type: 'loaded';
      id: number;
      failures: MeshFailure[];
      framed: FramedCamera;
    }
  | { type: 'loadFailed'; id: number; message: string }
  | { type: 'zones'; names: string[] }
  | {
      type: 'rendered';
      /** When the frame was drawn, ms since the Unix epoch (the worker's clock). */
      at: number;
      frames: number;
      /** The `seq` of the last resize this frame was drawn after (0: the size at init). */
      sizeSeq: number;
      pixelRatio: number;
      /** A frame's cost, ms, smoothed, where the frames run on a budget (software WebGL); else 0. */
      costMs: number;
      /** How far past the page's sample the pose drawn is, along the predicted course, ms. */
      aheadMs: number;
      robot: number[];
      ghost: number[];
      sibling: number[];
      ghostShows: 'nothing' | 'preview' | 'commanded' | 'plan' | 'refused';
      ghostPainted: string;
      /** The level each servo's link is painted at (../TrackingPaint.ts), null before a robot. */
      trackingLevels: string[] | null;
    }
  | { type: 'error'; message: string };
