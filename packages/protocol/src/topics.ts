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
] as const;
export type TopicKind = (typeof TOPIC_KINDS)[number];

export const isValidArmId = (armId: string): boolean => ARM_ID_PATTERN.test(armId);

export function assertArmId(armId: string): string {
  if (!isValidArmId(armId)) {
    throw new RangeError(`invalid arm id ${JSON.stringify(armId).slice(0, 40)}: expected [a-z0-9-]{1,32}`);
  }
  return armId;
}

export const topic = (armId: string, kind: TopicKind): string => `arm/${assertArmId(armId)}/${kind}`;

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
