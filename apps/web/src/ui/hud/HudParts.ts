/**
 * The plain objects the panels run on, built once by ../app/createHud.ts and handed down one
 * context each (./HudProvider.tsx). A panel names what it uses (`useArm()`, `useLink()`, …), and
 * each hook hands out the narrow side of its object (core/link/ArmCommands.ts style), never the
 * whole page. High-rate data stays out of React: the store is the plain object itself, which
 * panels sample (./useSampled.ts) and the render loop reads.
 */
import { createContext, useContext, type Context } from 'react';
import type { ArmStore } from '../../core/store/ArmStore.ts';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { ArmLink } from '../../core/link/ArmLink.ts';
import type { ArmCommands } from '../../core/link/ArmCommands.ts';
import type { HudSettings } from '../../core/config/settings.ts';
import type { ReplayPlayer } from '../../core/replay/ReplayPlayer.ts';
import type { Session } from '../../core/auth/Session.ts';
import type { RobotsHub } from '../../core/robots/RobotsHub.ts';
import type { RequestLog } from '../../core/robots/RequestLog.ts';
import type { CameraHub } from '../../core/cameras/CameraHub.ts';
import type { LeaderFeed } from '../../core/leader/LeaderFeed.ts';
import type { CameraScreens } from '../../scene/CameraScreens.ts';
import type { CalibrationSession } from '../../core/calibration/CalibrationSession.ts';
import type { HoldJog } from '../../core/jog/HoldJog.ts';
import type { GamepadJog } from '../../core/jog/GamepadJog.ts';
import type { RenderChoice } from '../../core/config/renderThread.ts';
import type { SceneView } from '../../scene/SceneView.ts';
import type { ModeSwitch } from '../../core/modes/ModeSwitch.ts';
import type { PlanTools } from './PlanTools.ts';

/** What the panels ask of the arm link: its commands, the control claim, and its figures. */
export type PanelLink = ArmCommands &
  Pick<ArmLink, 'control' | 'moveTo' | 'setTorque' | 'gap' | 'brokerInUse'>;

/** Switching arms or log-ins: a new link with new settings (Connection, Log-in, Fleet). */
export interface Reconnect {
  reconnect(settings: HudSettings): void;
  /** Controls another arm (the fleet list): saves it and reconnects. */
  selectArm(armId: string): void;
}

/** What composition builds; only ../app/createHud.ts, main.tsx and the provider see it whole. */
export interface HudParts {
  /** The live arm's plain store (sampled by panels, read by the render loop). */
  readonly store: ArmStore;
  readonly target: TargetPreview;
  /** The current MQTT link (replaced when the Connection panel reconnects). */
  link: ArmLink;
  settings: HudSettings;
  readonly reconnect: Reconnect;
  /** The History panel's replay, drawn as the sibling arm in the 3D view. */
  readonly replay: ReplayPlayer;
  /** Log-in state and the role's permissions (core/auth). */
  readonly session: Session;
  /** The fleet and the selected arm's robot (profile, model, planner). */
  readonly robots: RobotsHub;
  readonly plan: PlanTools;
  /** Motion requests this page sent (Command box, Cartesian panel) and their feedback. */
  readonly requests: RequestLog;
  /** The selected arm's cameras (PROTOCOL.md §7) and their screens in the 3D view. */
  readonly cameras: { readonly hub: CameraHub; readonly screens: CameraScreens };
  /** The selected arm's leader arms (`armtwin gateway --leader-of`): the ghost shows their pose. */
  readonly leaders: LeaderFeed;
  /** The calibration wizard of a bus arm (its ghost comes before the plan preview's). */
  readonly calibration: CalibrationSession;
  /** Hold-to-jog (buttons, keys, gamepad) of the Jog panel. */
  readonly jog: { readonly hold: HoldJog; readonly gamepad: GamepadJog };
  /** Model / Shadow / Twin for the selected arm (core/modes). */
  readonly modes: ModeSwitch;
  /** Where the 3D view is drawn (the page's thread or a worker), and why (Status panel). */
  rendering: RenderChoice;
  /** The 3D view's own figures, read by the Status and Ghost panels as they sample. */
  readonly view: SceneFigures;
}

/** The 3D view's figures a panel reads (never its scene). */
export type SceneFigures = Pick<SceneView, 'software' | 'frameCostMs' | 'reports'>;

type Contexts = { readonly [K in keyof HudParts]: Context<HudParts[K] | null> };

/** One context per part; ./HudProvider.tsx fills them all. */
export const HUD_CONTEXTS: Contexts = {
  store: createContext<ArmStore | null>(null),
  target: createContext<TargetPreview | null>(null),
  link: createContext<ArmLink | null>(null),
  settings: createContext<HudSettings | null>(null),
  reconnect: createContext<Reconnect | null>(null),
  replay: createContext<ReplayPlayer | null>(null),
  session: createContext<Session | null>(null),
  robots: createContext<RobotsHub | null>(null),
  plan: createContext<PlanTools | null>(null),
  requests: createContext<RequestLog | null>(null),
  cameras: createContext<HudParts['cameras'] | null>(null),
  leaders: createContext<LeaderFeed | null>(null),
  calibration: createContext<CalibrationSession | null>(null),
  jog: createContext<HudParts['jog'] | null>(null),
  modes: createContext<ModeSwitch | null>(null),
  rendering: createContext<RenderChoice | null>(null),
  view: createContext<SceneFigures | null>(null),
};

function usePart<K extends keyof HudParts>(key: K): HudParts[K] {
  const part = useContext(HUD_CONTEXTS[key]);
  if (part === null) throw new Error(`the HUD's ${key} used outside <HudProvider>`);
  return part;
}

/** The live arm's plain store. */
export const useArm = (): ArmStore => usePart('store');
/** The Cartesian target and the ghost's switch. */
export const useTarget = (): TargetPreview => usePart('target');
/** The current arm link, narrowed to what panels ask of it. */
export const useLink = (): PanelLink => usePart('link');
export const useSettings = (): Readonly<HudSettings> => usePart('settings');
export const useReconnect = (): Reconnect => usePart('reconnect');
export const useReplay = (): ReplayPlayer => usePart('replay');
/** Who this page is: the log-in state and the role's permissions. */
export const useSession = (): Pick<Session, 'state' | 'permissions' | 'error'> =>
  usePart('session');
/** The fleet and the selected arm's robot. */
export const useRobots = (): Pick<RobotsHub, 'active' | 'fleet'> => usePart('robots');
export const usePlan = (): PlanTools => usePart('plan');
export const useRequests = (): RequestLog => usePart('requests');
export const useCameras = (): HudParts['cameras'] => usePart('cameras');
/** The selected arm's leader arms: who drives it by a leader, and whether it still does. */
export const useLeaders = (): Pick<LeaderFeed, 'list' | 'version' | 'onGhost' | 'rejected'> =>
  usePart('leaders');
export const useCalibration = (): CalibrationSession => usePart('calibration');
export const useJog = (): HudParts['jog'] => usePart('jog');
export const useModes = (): Pick<ModeSwitch, 'mode' | 'note' | 'noteBad' | 'set' | 'driven'> =>
  usePart('modes');
export const useRendering = (): RenderChoice => usePart('rendering');
export const useSceneFigures = (): SceneFigures => usePart('view');
