/** armId: `[a-z0-9-]{1,32}`. The demo arm is `arm1`. */
export const ARM_ID_PATTERN = /^[a-z0-9-]{1,32}$/;
export const DEMO_ARM_ID = 'arm1';

/** The topics under `arm/{armId}/`. The first four are the contract's; the rest are armtwin's. */
export const TOPIC_KINDS = [
  'control',
  'status',
  'online',
  'operator',
  'profile',
  'request',
  'feedback',
  'sim',
  'torque',
  'summary',
  'alert',
] as const;
export type TopicKind = (typeof TOPIC_KINDS)[number];

export const isValidArmId = (armId: string): boolean => ARM_ID_PATTERN.test(armId);

/**
 * The model copy of arm `{id}` (docs/protocol.md § Modes) is the simulated arm `{id}-model`: an
 * id ending in `-model` is reserved for copies, so a real arm's id is at most
 * `MAX_REAL_ARM_ID_LENGTH` characters.
 */
export const MODEL_ARM_SUFFIX = '-model';
export const MAX_REAL_ARM_ID_LENGTH = 32 - MODEL_ARM_SUFFIX.length;
/** Whether `armId` names a model copy (ends in `-model`). */
export const isModelArmId = (armId: string): boolean => armId.endsWith(MODEL_ARM_SUFFIX);
/** The id of the model copy of arm `armId`; throws for an id that cannot have one. */
export function modelArmId(armId: string): string {
  if (!isValidArmId(armId) || isModelArmId(armId) || armId.length > MAX_REAL_ARM_ID_LENGTH)
    throw new RangeError(
      `arm ${JSON.stringify(armId).slice(0, 40)} has no model copy: a real arm id is [a-z0-9-]{1,${MAX_REAL_ARM_ID_LENGTH}}, not ending in ${MODEL_ARM_SUFFIX}`,
    );
  return armId + MODEL_ARM_SUFFIX;
}

export function assertArmId(armId: string): string {
  if (!isValidArmId(armId)) {
    throw new RangeError(
      `invalid arm id ${JSON.stringify(armId).slice(0, 40)}: expected [a-z0-9-]{1,32}`,
    );
  }
  return armId;
}

export const topic = (armId: string, kind: TopicKind): string =>
  `arm/${assertArmId(armId)}/${kind}`;

export type ArmTopics = Record<TopicKind, string>;
export function armTopics(armId: string): ArmTopics {
  assertArmId(armId);
  return Object.fromEntries(TOPIC_KINDS.map((k) => [k, `arm/${armId}/${k}`])) as ArmTopics;
}

/** `arm/+/{kind}`: every arm's topic of one kind. */
export const allArmsTopic = (kind: TopicKind): string => `arm/+/${kind}`;

const KIND_SET: ReadonlySet<string> = new Set(TOPIC_KINDS);

/** `arm/{armId}/{kind}` → parts, or null for any other topic (including a bad armId). */
export function parseTopic(name: string): { armId: string; kind: TopicKind } | null {
  const parts = name.split('/');
  if (parts.length !== 3 || parts[0] !== 'arm') return null;
  const [, armId, kind] = parts as [string, string, string];
  if (!isValidArmId(armId) || !KIND_SET.has(kind)) return null;
  return { armId, kind: kind as TopicKind };
}
