/**
 * The page's one composition root: builds every plain object the HUD runs on — settings, the
 * store, the target preview, the replay, the 3D view, the log-in session, the arm link, the
 * robots (fleet link and active robot), the Plan panel's objects, the request log and the
 * cameras — and
 * wires them to each other. Nothing below `hud/` builds or wires another part; `main.tsx` only
 * mounts what this returns.
 */
import {
  clearInterval as clearWorkerInterval,
  setInterval as setWorkerInterval,
} from 'worker-timers';
import { ArmStore } from '../../core/store/ArmStore.ts';
import { TargetPreview } from '../../core/store/TargetPreview.ts';
import { ArmLink, type IntervalTimers } from '../../core/link/ArmLink.ts';
import type { ConnectOptions } from '../../core/link/connectOptions.ts';
import { brokerConnect } from '../../core/link/brokerConnect.ts';
import { loadSettings, type HudSettings } from '../../core/config/settings.ts';
import { armQueryProblem } from '../../core/config/queryProblems.ts';
import { SceneClient } from '../../scene/render/SceneClient.ts';
import { IN_THREAD_HOSTING } from '../../scene/render/inThreadScene.ts';
import type { SceneView } from '../../scene/SceneView.ts';
import { FallbackSceneView } from '../../scene/render/FallbackSceneView.ts';
import {
  canRenderOffscreen,
  chooseRenderThread,
  fallbackChoice,
} from '../../core/config/renderThread.ts';
import { ReplayPlayer } from '../../core/replay/ReplayPlayer.ts';
import { Session } from '../../core/auth/Session.ts';
import { fetchWhoami } from '../../core/auth/whoami.ts';
import type { RobotView } from '../../core/robots/ActiveRobot.ts';
import { RobotsHub } from '../../core/robots/RobotsHub.ts';
import { settingsForArm } from '../../core/robots/selectArm.ts';
import { PlanPreview } from '../../core/plan/PlanPreview.ts';
import { PlanRunner } from '../../core/plan/PlanRunner.ts';
import { WaypointEditor } from '../../scene/WaypointEditor.ts';
import { Waypoints } from '../../core/plan/Waypoints.ts';
import { RunRecorder } from '../../core/plan/RunRecorder.ts';
import { RunReplay } from '../../core/plan/RunReplay.ts';
import { RequestLog } from '../../core/robots/RequestLog.ts';
import { CameraHub } from '../../core/cameras/CameraHub.ts';
import { CameraScreens } from '../../scene/CameraScreens.ts';
import { LeaderFeed } from '../../core/leader/LeaderFeed.ts';
import { CalibrationSession } from '../../core/calibration/CalibrationSession.ts';
import { HoldJog } from '../../core/jog/HoldJog.ts';
import { GamepadJog } from '../../core/jog/GamepadJog.ts';
import type { HudParts, Reconnect } from '../hud/HudParts.ts';
import type { PlanTools } from '../hud/PlanTools.ts';
import { installDebugHook } from './debugHook.ts';
import { ModeSwitch } from '../../core/modes/ModeSwitch.ts';
import { SiblingFeed } from '../../core/modes/SiblingFeed.ts';

/** The page's elements: the 3D view's container and the line that says the model is loading. */
export interface HudElements {
  view: HTMLElement;
  message: HTMLElement;
}

export interface HudPage {
  readonly parts: HudParts;
  /** Connects, loads the robot model and starts the 3D view. */
  start(): void;
}

/**
 * mqtt.js for both of the page's clients (the arm link and the fleet link), over the settings'
 * broker list (../../core/link/brokerConnect.ts).
 */
const connect = (url: string, opts: ConnectOptions) => brokerConnect(url, opts);

/** The deadman's beat keeps time in a worker: a hidden tab is not throttled into a stop. */
const workerIntervals: IntervalTimers = {
  setInterval: (fn, ms) => setWorkerInterval(fn, ms),
  clearInterval: (id) => clearWorkerInterval(id),
};

const polaritiesOf = (arm: ArmStore['opts']['arm']): number[] => arm.servos.map((s) => s.polarity);

/** `render(parts)` draws the panels; it is called whenever what they show changes shape. */
export function createHud(els: HudElements, render: (parts: HudParts) => void): HudPage {
  const settings = loadSettings();
  const store = new ArmStore({
    interpolationAlpha: settings.interpolationAlpha,
    twinMode: settings.twinMode,
  });
  const target = new TargetPreview();
  const replay = new ReplayPlayer();
  // Model / Shadow / Twin: applied to each new link once its role is known.
  const modes = new ModeSwitch({
    location: window.location,
    replaceUrl: (url) => window.history.replaceState(window.history.state, '', url),
    storage: (() => {
      try {
        return window.sessionStorage;
      } catch {
        return null;
      }
    })(),
  });
  // The translucent sibling: the replay, else (Model mode) the model copy beside the arm.
  const sibling = new SiblingFeed(replay, () => (modes.mode === 'model' ? modes.copy : null));
  // The 3D view draws in a worker (OffscreenCanvas) when possible and not told otherwise, else
  // here; a worker that fails before its first frame hands over to the main thread.
  let rendering = chooseRenderThread(window.location.search, canRenderOffscreen());
  let built = false; // the fallback may come while the viewer is built, before `hud` is
  const mainView = () =>
    new SceneClient(els.view, store, target, sibling, false, IN_THREAD_HOSTING);
  const viewer: SceneView =
    rendering.thread === 'worker'
      ? new FallbackSceneView(
          {
            worker: () => new SceneClient(els.view, store, target, sibling, rendering.pace),
            main: mainView,
          },
          (reason) => {
            console.warn(
              `3D view: drawing on the main thread, the render worker failed: ${reason}`,
            );
            rendering = fallbackChoice(reason, rendering.pace);
            if (!built) return;
            hud.rendering = rendering;
            render(hud);
          },
        )
      : mainView();
  const session = new Session({
    whoami: (s) => fetchWhoami(s.apiBase, s),
    queryProblem: armQueryProblem(window.location.search),
  });
  // The active robot is shown by the 3D view and replayed by the sibling, both in its terms.
  const view: RobotView = {
    show(spec, urdfUrl) {
      replay.configure(
        polaritiesOf(spec.storeArm),
        spec.storeArm.servos.map((s) => s.id),
      );
      viewer.showZones(spec.profile.keepOut);
      return viewer.load(urdfUrl, spec.joints);
    },
  };
  const robots = new RobotsHub(store, view, connect, settings, () => render(hud));
  const plan: PlanTools = {
    waypoints: new Waypoints(),
    preview: new PlanPreview(),
    runner: new PlanRunner(),
    editor: null,
    recorder: new RunRecorder(),
    runReplay: new RunReplay(replay),
  };
  const requests = new RequestLog();
  const calibration = new CalibrationSession(store);
  // The cameras ride on the arm link's client: it is rebuilt for each arm and log-in, so the
  // list follows the selected arm and reads with the page's credentials and role.
  const cameras = new CameraHub();
  // The leader arms ride on it too (their poses: the ghost, below).
  const leaders = new LeaderFeed(
    () => store.opts.arm.servos,
    () => performance.now(),
  );
  const firstLink = new ArmLink(store, settings, connect, workerIntervals);
  cameras.attach(firstLink);
  leaders.attach(firstLink);
  const cameraScreens = new CameraScreens(viewer, cameras, cameras.decoders);
  // Hold-to-jog reads the link live (it is replaced on reconnect); the e-stop lets go of it.
  const hold = new HoldJog({
    // Holds step from the driven arm's pose: the model copy's in Model mode.
    get store() {
      return modes.driven(store);
    },
    link: () => hud.link,
    robot: () => ({ sliders: robots.active.spec.sliders, motion: robots.active.motion }),
    ghost: target,
  });
  const gamepad = new GamepadJog(hold, () => hud.link.emergencyStop(), {
    getGamepads: () => navigator.getGamepads?.() ?? [],
    requestAnimationFrame: (fn) => window.requestAnimationFrame(fn),
    cancelAnimationFrame: (h) => window.cancelAnimationFrame(h),
    addEventListener: (t, fn) => window.addEventListener(t, fn),
    removeEventListener: (t, fn) => window.removeEventListener(t, fn),
    storage: window.localStorage,
  });
  const letGoOnStop = (link: ArmLink) => link.stopListeners.add(() => hold.releaseAll(false));
  letGoOnStop(firstLink);
  const startSession = (link: ArmLink) =>
    void session.start(link).then(() => {
      if (hud.link === link) modes.attach(link, store);
      render(hud);
    });

  const reconnect: Reconnect = {
    selectArm(armId: string) {
      const next = settingsForArm(hud.settings, armId);
      if (next) reconnect.reconnect(next);
    },
    reconnect(next: HudSettings) {
      hold.releaseAll();
      hud.link.stop();
      store.resetArm();
      store.setInterpolationAlpha(next.interpolationAlpha);
      store.setTwinMode(next.twinMode);
      const prev = hud.settings;
      hud.settings = next;
      hud.link = new ArmLink(store, next, connect, workerIntervals);
      cameras.attach(hud.link);
      leaders.attach(hud.link);
      letGoOnStop(hud.link);
      plan.runner.cancel(prev.armId === next.armId ? '' : 'stopped: another arm was selected');
      plan.preview.clear();
      if (prev.armId !== next.armId) plan.recorder.clear();
      robots.switched(prev, next);
      startSession(hud.link);
      render(hud);
    },
  };
  const hud: HudParts = {
    store,
    target,
    replay,
    settings,
    reconnect,
    session,
    robots,
    plan,
    requests,
    cameras: { hub: cameras, screens: cameraScreens },
    leaders,
    calibration,
    jog: { hold, gamepad },
    modes,
    rendering,
    view: viewer,
    link: firstLink,
  };

  built = true;

  // The ghost runs along the plan being previewed, and along each re-plan of a run.
  // (the calibration wizard's ghost, while it is open, comes first); else it shows where a
  // leader arm asks the arm to go.
  viewer.ghostSource = {
    sample: (now, out) =>
      calibration.sample(now, out) ||
      plan.runReplay.sample(now, out) || // "Replay run": the rehearsal beside the actual run
      plan.preview.sample(now, out)
        ? leaders.notShown()
        : leaders.sample(now, out),
  };
  plan.runner.onPlan((p) => plan.preview.show(p, polaritiesOf(store.opts.arm), performance.now()));
  plan.runner.onEnd(() => plan.preview.clear()); // the ghost goes when the plan is over
  plan.runner.onEnd((state) => plan.recorder.end(state === 'done')); // rehearsal / actual run
  robots.onFeedback((f) => requests.take(f));
  const debug = installDebugHook(hud, viewer);

  function start(): void {
    startSession(hud.link);
    // Let go of the arm when the page goes away (the deadman's `0` at once, not after the will).
    window.addEventListener('pagehide', () => hud.link.release());
    window.addEventListener('pageshow', (e) => e.persisted && reconnect.reconnect(hud.settings));
    hold.attach(window, document);
    gamepad.start();
    render(hud);
    els.message.textContent = 'Loading the arm model…';
    robots.start(settings.armId);
    robots.active.firstLoad
      .then(() => {
        els.message.hidden = true;
        viewer.start();
        plan.editor ??= new WaypointEditor(viewer, plan.waypoints);
        debug.ready = true;
        render(hud);
      })
      .catch((err: unknown) => {
        els.message.classList.add('error');
        els.message.setAttribute('role', 'alert');
        els.message.textContent = `The arm model failed to load: ${err instanceof Error ? err.message : String(err)}`;
        render(hud); // the panels still work without the 3D view
      });
  }

  return { parts: hud, start };
}
