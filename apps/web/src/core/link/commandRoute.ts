/**
 * Where a command from the page goes (docs/protocol.md § Modes, § Control): routed by the mode
 * (./modes.ts `commandTopic`): to the arm in Twin, to its copy in Model, nowhere in Shadow;
 * and only while nobody else holds the driven arm, unless it is stops only. Pure: ArmLink
 * (./ArmLink.ts) publishes what this allows and says why it did not.
 */
import { STOPS_ONLY } from '@armtwin/protocol';
import { commandTopic, type ArmMode } from './modes.ts';
import type { ControlClaim } from './ControlClaim.ts';

/** The user of a claim's per-user topics, null for the plain topic (ControlClaim's rule). */
export function claimUser(claim: ControlClaim): string | null {
  return claim.ownTopics ? claim.who.name : null;
}

/** The topic a command goes out on, or why it is not sent. */
export type CommandRoute = { to: string; refused?: undefined } | { to: null; refused: string };

/**
 * Routes `payload` for the arm `armId` in `mode`, `claim` being the page's claim on the driven
 * arm. A command (`isCommand`; a ping is not) is refused while another user holds that arm.
 */
export function routeCommand(
  armId: string,
  mode: ArmMode,
  claim: ControlClaim,
  payload: string,
  isCommand: boolean,
): CommandRoute {
  const to = commandTopic(armId, mode, claimUser(claim));
  if (to === null) return { to, refused: 'not sent: Shadow mode sends no commands' };
  // A payload of stops only is sent whoever holds the arm (the e-stop wins over everything).
  if (isCommand && !claim.mayMove && !STOPS_ONLY.test(payload))
    return { to: null, refused: `not sent: ${claim.heldBy} controls the arm` };
  return { to };
}
