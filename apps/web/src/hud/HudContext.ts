/** The plain objects every panel reads: created once in main.tsx, handed down by context. */
import { createContext, useContext } from 'react';
import type { ArmStore } from '../store/ArmStore.ts';
import type { TargetPreview } from '../store/TargetPreview.ts';
import type { ArmLink } from '../mqtt/ArmLink.ts';
import type { HudSettings } from '../config/settings.ts';
import type { ReplayPlayer } from '../replay/ReplayPlayer.ts';
import type { Session } from '../auth/Session.ts';
import type { RobotsHub } from '../robots/RobotsHub.ts';

export interface Hud {
  store: ArmStore;
  target: TargetPreview;
  /** The current MQTT link (replaced when the Connection panel reconnects). */
  link: ArmLink;
  settings: HudSettings;
  /** The History panel's replay, drawn as the sibling arm by the Viewer. */
  replay: ReplayPlayer;
  /** Log-in state and the role's permissions (src/auth). */
  session: Session;
  reconnect(settings: HudSettings): void;
  /** Fleet, the selected arm's robot profile, planning (issue 9, src/robots). */
  robots: RobotsHub;
  /** Controls another arm (the fleet list): saves it and reconnects. */
  selectArm(armId: string): void;
}

export const HudContext = createContext<Hud | null>(null);

export function useHud(): Hud {
  const hud = useContext(HudContext);
  if (!hud) throw new Error('useHud outside <HudContext>');
  return hud;
}
