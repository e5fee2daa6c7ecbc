/** The plain objects every panel reads: built once in ../app/createHud.ts, handed down by context. */
import { createContext, useContext } from 'react';
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { ArmLink } from '../../core/link/ArmLink.ts';
import type { HudSettings } from '../../core/config/settings.ts';
import type { ReplayPlayer } from '../../core/replay/ReplayPlayer.ts';
import type { Session } from '../../core/auth/Session.ts';
import type { RobotsHub } from '../../core/robots/RobotsHub.ts';
import type { Waypoints } from '../../core/plan/Waypoints.ts';
import type { PlanPreview } from '../../core/plan/PlanPreview.ts';
import type { PlanRunner } from '../../core/plan/PlanRunner.ts';
import type { WaypointEditor } from '../../scene/WaypointEditor.ts';
import type { RunRecorder } from '../../core/plan/RunRecorder.ts';
import type { RunReplay } from '../../core/plan/RunReplay.ts';
import type { RequestLog } from '../../core/robots/RequestLog.ts';
import type { CameraHub } from '../../core/cameras/CameraHub.ts';
import type { CameraScreens } from '../../scene/CameraScreens.ts';
import type { CalibrationSession } from '../../core/calibration/CalibrationSession.ts';
import type { HoldJog } from '../../core/jog/HoldJog.ts';
import type { GamepadJog } from '../../core/jog/GamepadJog.ts';
import type { RenderChoice } from '../../core/config/renderThread.ts';
import type { SceneView } from '../../scene/SceneView.ts';
import type { ModeSwitch } from '../../core/modes/ModeSwitch.ts';

/** The Plan panel's plain objects. */
export interface PlanTools {
  readonly waypoints: Waypoints;
  /** What the ghost runs along (the 3D view's ghost source). */
  readonly preview: PlanPreview;
  /** Streams a plan to the arm with pose checking. */
  readonly runner: PlanRunner;
  /** The waypoint spheres in 3D (once the 3D view has started). */
  editor: WaypointEditor | null;
  /** Rehearse, then run: the rehearsal in Model mode, the actual run, their tracking error. */
  readonly recorder: RunRecorder;
  /** "Replay run": the actual run as the replay's sibling, the rehearsal as the ghost. */
  readonly runReplay: RunReplay;
}

export interface Hud {
  store: ArmStore;
  target: TargetPreview;
  /** The current MQTT link (replaced when the Connection panel reconnects). */
  link: ArmLink;
  settings: HudSettings;
  /** The History panel's replay, drawn as the sibling arm in the 3D view. */
  replay: ReplayPlayer;
  /** Log-in state and the role's permissions (src/auth). */
  session: Session;
  reconnect(settings: HudSettings): void;
  /** The fleet and the selected arm's robot (profile, model, planner). */
  robots: RobotsHub;
  plan: PlanTools;
  /** Motion requests this page sent (Command box, Cartesian panel) and their feedback. */
  requests: RequestLog;
  /** The selected arm's cameras (PROTOCOL.md §7), read on the arm link's client. */
  cameras: CameraHub;
  /** The cameras' screens in the 3D view, and "view through this camera". */
  cameraScreens: CameraScreens;
  /** The calibration wizard of a bus arm (its ghost comes before the plan preview's). */
  calibration: CalibrationSession;
  /** Hold-to-jog (buttons, keys, gamepad) of the Jog panel. */
  jog: { hold: HoldJog; gamepad: GamepadJog };
  /** Model / Shadow / Twin for the selected arm (src/modes). */
  modes: ModeSwitch;
  /** Controls another arm (the fleet list): saves it and reconnects. */
  selectArm(armId: string): void;
  /** Where the 3D view is drawn (the page's thread or a worker), and why (Status panel). */
  rendering: RenderChoice;
  /** The 3D view's own figures, read by the Status panel as it samples. */
  view: Pick<SceneView, 'software' | 'frameCostMs' | 'reports'>;
}

export const HudContext = createContext<Hud | null>(null);

export function useHud(): Hud {
  const hud = useContext(HudContext);
  if (!hud) throw new Error('useHud outside <HudContext>');
  return hud;
}
