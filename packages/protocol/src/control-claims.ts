/**
 * Who holds an arm (docs/protocol.md, "Control: one operator at a time"): the per-user topics
 * that carry a user's identity, the claim words, the retained holder record and the audit
 * events. Identity is the topic's last level: with authentication on, the broker's ACL lets a
 * user write only the topics that end in their own name, so a message on
 * `arm/arm1/control/alice` can only have come from alice. Pure: no I/O.
 */
import { assertArmId, isValidArmId, parseTopic } from './topics.ts';

/** The per-user topic kinds under `arm/{id}/`: `…/{kind}/{user}` (`request`: motion requests). */
export const USER_TOPIC_KINDS = ['control', 'claim', 'override', 'request'] as const;
export type UserTopicKind = (typeof USER_TOPIC_KINDS)[number];

/** A user name as the users file allows it (and a self-declared name in the anonymous demo). */
export const CONTROL_USER_PATTERN = /^[A-Za-z0-9._-]{1,64}$/;

/** `arm/{id}/{kind}/{user}`. */
export function userTopic(armId: string, kind: UserTopicKind, user: string): string {
  if (!CONTROL_USER_PATTERN.test(user))
    throw new RangeError(`invalid user name ${JSON.stringify(user).slice(0, 40)}`);
  return `arm/${assertArmId(armId)}/${kind}/${user}`;
}

/** `arm/{id}/{kind}/{user}` → parts, or null for any other topic. */
export function parseUserTopic(
  name: string,
): { armId: string; kind: UserTopicKind; user: string } | null {
  const parts = name.split('/');
  if (parts.length !== 4 || parts[0] !== 'arm') return null;
  const [, armId, kind, user] = parts as [string, string, string, string];
  if (!isValidArmId(armId) || !(USER_TOPIC_KINDS as readonly string[]).includes(kind)) return null;
  if (!CONTROL_USER_PATTERN.test(user)) return null;
  return { armId, kind: kind as UserTopicKind, user };
}

/** The retained record of who holds the arm: `arm/{id}/holder`. */
export const holderTopic = (armId: string) => `arm/${assertArmId(armId)}/holder`;
/** Control events, not retained: `arm/{id}/audit`. */
export const auditTopic = (armId: string) => `arm/${assertArmId(armId)}/audit`;

/**
 * What a user says on `arm/{id}/claim/{user}`: `take`, `beat` (the holder's keep-alive),
 * `ask`, `grant <user>`, `refuse <user>`, `release`. On `…/override/{user}` only `take`.
 */
export type Claim =
  | { op: 'take' }
  | { op: 'beat' }
  | { op: 'ask' }
  | { op: 'release' }
  | { op: 'grant'; to: string }
  | { op: 'refuse'; to: string };

const decoder = new TextDecoder();
const asText = (payload: string | Uint8Array) =>
  typeof payload === 'string' ? payload : decoder.decode(payload);

/** The claim in a payload, or an error message saying what was wrong with it. */
export function parseClaim(payload: Uint8Array | string): Claim | { error: string } {
  const text = asText(payload).trim();
  const [word, to, ...rest] = text.split(/\s+/);
  if (rest.length === 0) {
    if (to === undefined && (word === 'take' || word === 'beat' || word === 'ask'))
      return { op: word };
    if (to === undefined && word === 'release') return { op: 'release' };
    if ((word === 'grant' || word === 'refuse') && to !== undefined) {
      if (CONTROL_USER_PATTERN.test(to)) return { op: word, to };
      return { error: `${word}: not a user name` };
    }
  }
  return {
    error: `unknown claim ${JSON.stringify(text.slice(0, 40))}: expected take, beat, ask, grant <user>, refuse <user> or release`,
  };
}

export const HOLDER_ROLES = ['operator', 'admin'] as const;
export type HolderRole = (typeof HOLDER_ROLES)[number];

/** `arm/{id}/holder` (retained JSON). `user` null: nobody holds the arm. */
export interface HolderRecord {
  user: string | null;
  role?: HolderRole;
  /** When the holder took (or was granted) the arm, epoch ms. */
  since?: number;
  /** Users who asked for the arm, oldest first (only while someone holds it). */
  requests: string[];
}

export const AUDIT_KINDS = [
  'taken',
  'asked',
  'granted',
  'refused',
  'withdrawn',
  'released',
  'lost',
  'admin-take-over',
  'refused-command',
  'refused-claim',
  'e-stop',
  'e-stop-released',
  'refused-keep-out',
] as const;
export type AuditKind = (typeof AUDIT_KINDS)[number];

/** One control event on `arm/{id}/audit`. `by`: the user it came from ('' = the plain topic). */
export interface AuditEvent {
  at: number;
  by: string;
  kind: AuditKind;
  detail: string;
}

/** A holder record or audit event read back (the HUD); null when the JSON is not one. */
export function parseHolder(payload: Uint8Array | string): HolderRecord | null {
  const text = asText(payload);
  if (text.trim() === '') return { user: null, requests: [] };
  try {
    const v = JSON.parse(text) as Partial<HolderRecord>;
    if (v.user !== null && (typeof v.user !== 'string' || !CONTROL_USER_PATTERN.test(v.user)))
      return null;
    const requests = Array.isArray(v.requests)
      ? v.requests.filter((r): r is string => typeof r === 'string' && CONTROL_USER_PATTERN.test(r))
      : [];
    return {
      user: v.user,
      ...(v.role && (HOLDER_ROLES as readonly string[]).includes(v.role) ? { role: v.role } : {}),
      ...(typeof v.since === 'number' ? { since: v.since } : {}),
      requests: v.user === null ? [] : requests,
    };
  } catch {
    return null;
  }
}

export function parseAudit(payload: Uint8Array | string): AuditEvent | null {
  const text = asText(payload);
  try {
    const v = JSON.parse(text) as Partial<AuditEvent>;
    if (typeof v.at !== 'number' || typeof v.by !== 'string' || typeof v.detail !== 'string')
      return null;
    if (!(AUDIT_KINDS as readonly string[]).includes(v.kind as string)) return null;
    return { at: v.at, by: v.by, kind: v.kind as AuditKind, detail: v.detail };
  } catch {
    return null;
  }
}

/** A payload of stops only (`#IIIPDST!`…, the e-stop `#255PDST!` among them). */
export const STOPS_ONLY = /^(#\d{3}PDST!)+$/;

/**
 * Whether a message perishes with the connection it was published on: sent on that connection
 * or never, not re-sent on the next one (docs/protocol.md § Several brokers). Claims and
 * overrides (`…/claim/{user}`, `…/override/{user}`: a late `take` would take control without a
 * click) and commands and motion requests (`…/control[/{user}]`, `…/request[/{user}]`: a late
 * move runs when nobody expects it), except a payload of stops only: the stop wins, late or not.
 */
export function perishesWithConnection(topic: string, payload: string | Uint8Array): boolean {
  const kind = parseUserTopic(topic)?.kind ?? parseTopic(topic)?.kind;
  if (kind === 'claim' || kind === 'override') return true;
  if (kind === 'control' || kind === 'request') return !STOPS_ONLY.test(asText(payload));
  return false;
}
