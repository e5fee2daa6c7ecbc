/**
 * An arm's summary on `arm/{armId}/summary` (docs/protocol.md § Fleets: the summary topic): what
 * a fleet view needs of an arm that is not the one shown, at a slow rate. Published retained by
 * whoever runs the arm's controller core (the sim, the bus, LSC and ROS 2 gateways, through
 * `@armtwin/controller/mqtt`'s `startArmSummary`) every `SUMMARY_PERIOD_MS`, and at once (no
 * sooner than `SUMMARY_MIN_GAP_MS` after the last) when its health level or its last `$ERR`
 * changes, so a page that follows only summaries still sees an alarm at once. JSON; pure.
 */
import type { HealthLevel } from './health.ts';

/** A summary every 500 ms (2 Hz) while the arm's client is connected. */
export const SUMMARY_PERIOD_MS = 500;
/** The soonest an alarm's summary follows the last one, ms (a flood of `$ERR` stays ≤ 10/s). */
export const SUMMARY_MIN_GAP_MS = 100;
/** An arm's summary is at most this long, bytes (far more than 32 joints take). */
export const SUMMARY_MAX_BYTES = 8192;

/** `moving`: a joint is on its way; `still`; `not-ready`: goals cannot be carried out (`why`). */
export const ARM_STATES = ['moving', 'still', 'not-ready'] as const;
export type ArmState = (typeof ARM_STATES)[number];

/** One joint: its servo id, its servo angle now and its limits, degrees (0.1° steps). */
export interface SummaryJoint {
  id: number;
  deg: number;
  min: number;
  max: number;
}

export interface ArmSummary {
  /** When it was made, the publisher's clock (epoch ms). */
  t: number;
  state: ArmState;
  /** Why it is not ready ('' otherwise). */
  why: string;
  /** The worst health level over the servos' latest reports (PROTOCOL.md §5). */
  health: HealthLevel | 'unknown';
  /** Which servos are not normal, in words ('' when none): `healthSummary`'s. */
  alarm: string;
  /** Who holds the arm (`arm/{id}/holder`'s user), null when nobody does. */
  holder: string | null;
  joints: SummaryJoint[];
  /** The arm's last `$ERR` and when (null before any). */
  error: { t: number; text: string } | null;
}

export const encodeSummary = (s: ArmSummary): string => JSON.stringify(s);

export type SummaryParse = { ok: true; summary: ArmSummary } | { ok: false; error: string };

const isNum = (v: unknown): v is number => typeof v === 'number' && Number.isFinite(v);
const isObj = (v: unknown): v is Record<string, unknown> =>
  typeof v === 'object' && v !== null && !Array.isArray(v);
const LEVELS: readonly unknown[] = ['normal', 'warning', 'critical', 'unknown'];
const fail = (error: string): SummaryParse => ({ ok: false, error });

/** A summary payload → the summary, or why not (the first problem found). */
export function parseSummary(payload: Uint8Array | string): SummaryParse {
  if (payload.length > SUMMARY_MAX_BYTES) return fail(`over ${SUMMARY_MAX_BYTES} bytes`);
  let v: unknown;
  try {
    v = JSON.parse(typeof payload === 'string' ? payload : new TextDecoder().decode(payload));
  } catch {
    return fail('not JSON');
  }
  if (!isObj(v)) return fail('not an object');
  if (!isNum(v.t)) return fail('t: not a number');
  if (!(ARM_STATES as readonly unknown[]).includes(v.state)) return fail('state: unknown');
  if (typeof v.why !== 'string') return fail('why: not a string');
  if (!LEVELS.includes(v.health)) return fail('health: unknown level');
  if (typeof v.alarm !== 'string') return fail('alarm: not a string');
  if (v.holder !== null && typeof v.holder !== 'string') return fail('holder: not a string');
  if (!Array.isArray(v.joints)) return fail('joints: not an array');
  const joints: SummaryJoint[] = [];
  for (const j of v.joints as unknown[]) {
    if (!isObj(j) || !isNum(j.id) || !isNum(j.deg) || !isNum(j.min) || !isNum(j.max))
      return fail('joints: each needs numbers id, deg, min, max');
    joints.push({ id: j.id, deg: j.deg, min: j.min, max: j.max });
  }
  const e = v.error;
  if (e !== null && !(isObj(e) && isNum(e.t) && typeof e.text === 'string'))
    return fail('error: not null or {t, text}');
  return {
    ok: true,
    summary: {
      t: v.t,
      state: v.state as ArmState,
      why: v.why,
      health: v.health as ArmSummary['health'],
      alarm: v.alarm,
      holder: v.holder as string | null,
      joints,
      error: e === null ? null : { t: e.t as number, text: e.text as string },
    },
  };
}
