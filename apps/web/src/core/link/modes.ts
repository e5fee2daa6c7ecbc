/**
 * Model / Shadow / Twin (issue 20, seed 003; docs/protocol.md § Modes): which arm this page's
 * commands drive. Twin drives the real arm `arm/{id}/…`; Model drives its simulated copy
 * `arm/{id}-model/…` (started by `armtwin up` on demand); Shadow drives nothing — only the
 * emergency stop goes out, to the real arm. Pure: no I/O.
 */
import {
  isModelArmId,
  MODEL_ARM_SUFFIX,
  modelArmId as copyIdOf,
  topic,
  userTopic,
} from '@armtwin/protocol';

export { isModelArmId, MODEL_ARM_SUFFIX };

export type ArmMode = 'model' | 'shadow' | 'twin';

/** The switch's buttons, in order, with their names on the page. */
export const ARM_MODES: ReadonlyArray<{ mode: ArmMode; label: string; title: string }> = [
  { mode: 'model', label: 'Model', title: 'Commands go to a simulated copy of this arm' },
  { mode: 'shadow', label: 'Shadow', title: 'Mirror the arm: every control is off' },
  { mode: 'twin', label: 'Twin', title: 'Commands drive the real arm' },
];

/** Said on every control while in Shadow mode. */
export const SHADOW_REASON = 'Shadow mode: the page only mirrors the arm. Choose Twin to drive it.';

/**
 * The id of arm `armId`'s model copy (`{id}-model`), null for an arm that cannot have one (a
 * copy itself, or an id longer than 26 characters): Model mode is then not offered.
 */
export function modelArmId(armId: string): string | null {
  try {
    return copyIdOf(armId);
  } catch {
    return null;
  }
}

export function parseMode(s: string | null | undefined): ArmMode | null {
  return s === 'model' || s === 'shadow' || s === 'twin' ? s : null;
}

/** A page whose role may drive opens in Twin (as before modes); a viewer in Shadow. */
export function defaultMode(mayCommand: boolean): ArmMode {
  return mayCommand ? 'twin' : 'shadow';
}

/** The arm whose control topics a command goes to in `mode`; null = none (Shadow). */
export function commandArm(armId: string, mode: ArmMode): string | null {
  if (mode === 'shadow') return null;
  return mode === 'model' ? modelArmId(armId) : armId;
}

/**
 * The topic a command goes to: the driven arm's per-user control topic (`user` set: logged in,
 * or holding it) or its plain one; null in Shadow mode, where only stops go out.
 */
export function commandTopic(armId: string, mode: ArmMode, user: string | null): string | null {
  const arm = commandArm(armId, mode);
  if (arm === null) return null;
  return user ? userTopic(arm, 'control', user) : topic(arm, 'control');
}

/**
 * Where the emergency stop goes: always the real arm, and in Model mode the copy as well (the
 * stop wins over every mode: a stop pressed while rehearsing also stops the real arm).
 */
export function stopArms(armId: string, mode: ArmMode): string[] {
  const copy = mode === 'model' ? modelArmId(armId) : null;
  return copy ? [copy, armId] : [armId];
}
