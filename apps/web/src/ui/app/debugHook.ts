/**
 * `window.__armtwin`: the page's objects for the end-to-end tests, the bench's probe and the
 * console. Read-only by convention (apps/web/README.md § Debug hook).
 */
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { ArmLink } from '../../core/link/ArmLink.ts';
import type { DrawnRobot, SceneView } from '../../scene/SceneView.ts';
import { readTimeStripe, timeStripeLayout } from '@armtwin/camera/client';
import type { ReplayPlayer } from '../../core/replay/ReplayPlayer.ts';
import type { Session } from '../../core/auth/Session.ts';
import type { ActiveRobot } from '../../core/robots/ActiveRobot.ts';
import type { FleetLink } from '../../core/robots/FleetLink.ts';
import { historyProbe } from '../panels/History/probe.ts';
import type { HudParts } from '../hud/HudParts.ts';
import { FallbackSceneView } from '../../scene/render/FallbackSceneView.ts';

export interface DebugHook {
  store: ArmStore;
  target: TargetPreview;
  /** The 3D view: the page side of the scene runtime (in the render worker or on this thread). */
  readonly viewer: SceneView;
  readonly link: ArmLink;
  /** Set once the first robot model has loaded and the 3D view runs. */
  ready: boolean;
  replay: ReplayPlayer;
  history: typeof historyProbe;
  session: Session;
  /** Model / Shadow / Twin, the model copy's store, and the Plan panel's rehearsal recorder. */
  modes: HudParts['modes'];
  recorder: HudParts['plan']['recorder'];
  /** The fleet, the active robot, and the Plan panel's objects. */
  robots: {
    readonly fleet: FleetLink;
    active: ActiveRobot;
    waypoints: HudParts['plan']['waypoints'];
    preview: HudParts['plan']['preview'];
    runner: HudParts['plan']['runner'];
    readonly editor: HudParts['plan']['editor'];
    requests: HudParts['requests'];
  };
  /**
   * The URDF joint values a robot is drawn with (rad, or m for a prismatic joint), servo order:
   * the live arm (default), the ghost, or the replay's sibling.
   */
  joints(which?: DrawnRobot): number[];
  /**
   * The camera package's time-stripe reader, for the bench's glass-to-glass probe
   * (bench/lib/camera-probe.ts reads it from the canvas a camera view displays).
   */
  timeStripe: { read: typeof readTimeStripe; layout: typeof timeStripeLayout };
}

declare global {
  interface Window {
    __armtwin?: DebugHook;
  }
}

/** Installs the hook; `hud` is read live (its link and settings are replaced on reconnect). */
export function installDebugHook(hud: HudParts, viewer: SceneView): DebugHook {
  const { robots, plan } = hud;
  const hook: DebugHook = {
    store: hud.store,
    target: hud.target,
    // The view drawing now (after a worker's failure: the main-thread one that took over).
    get viewer() {
      return viewer instanceof FallbackSceneView ? viewer.view : viewer;
    },
    get link() {
      return hud.link;
    },
    ready: false,
    replay: hud.replay,
    history: historyProbe,
    session: hud.session,
    modes: hud.modes,
    recorder: plan.recorder,
    robots: {
      get fleet() {
        return robots.fleet;
      },
      active: robots.active,
      waypoints: plan.waypoints,
      preview: plan.preview,
      runner: plan.runner,
      get editor() {
        return plan.editor;
      },
      requests: hud.requests,
    },
    joints: (which) => viewer.jointValues(which),
    timeStripe: { read: readTimeStripe, layout: timeStripeLayout },
  };
  window.__armtwin = hook;
  return hook;
}
