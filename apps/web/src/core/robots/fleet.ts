/**
 * The fleet: every arm seen on the broker, from the retained `arm/+/online`, `arm/+/profile` and
 * `arm/+/summary` (state, worst health, holder, pose at 2 Hz and at once on an alarm,
 * docs/protocol.md § Fleets), and the thermal model's early warnings on `arm/+/alert`. The
 * fleet never reads another arm's full-rate status. A pure reducer: each event → a new state
 * (the same object when nothing changed); `sameSummary` tells whether an arm's row looks different.
 */
import {
  isValidArmId,
  type ArmState,
  type ArmSummary,
  type HealthLevel,
  type SummaryJoint,
} from '@armtwin/protocol';
import type { ThermalAlert } from '@armtwin/thermal';

export interface FleetArm {
  readonly id: string;
  /** Retained `online`: true, false, or null before it is known. */
  readonly online: boolean | null;
  /** From the retained profile: its name and title (null until one is announced). */
  readonly profileName: string | null;
  readonly title: string | null;
  /** From the arm's summary: the worst health level ('unknown' before any) and its words. */
  readonly level: HealthLevel | 'unknown';
  readonly alarm: string;
  /** From the summary: moving, still or not ready (null before a summary). */
  readonly state: ArmState | null;
  /** Why it is not ready ('' otherwise). */
  readonly why: string;
  /** Who holds it (null: nobody, or no summary yet). */
  readonly holder: string | null;
  /** Servo angles and their limits, degrees (the row's small pose). */
  readonly joints: readonly SummaryJoint[];
  /** The arm's last `$ERR` (null before any). */
  readonly error: ArmSummary['error'];
  /** The thermal model's early warnings in force, by servo (`002` → the sentence). */
  readonly warnings: Readonly<Record<string, string>>;
}

export type FleetState = ReadonlyMap<string, FleetArm>;

export type FleetEvent =
  | { kind: 'online'; id: string; text: string }
  | { kind: 'profile'; id: string; name: string | null; title: string | null }
  /** A summary, or null when the retained one was cleared. */
  | { kind: 'summary'; id: string; summary: ArmSummary | null }
  | { kind: 'alert'; id: string; alert: ThermalAlert };

export const EMPTY_FLEET: FleetState = new Map();

const NO_SUMMARY = {
  level: 'unknown',
  alarm: '',
  state: null,
  why: '',
  holder: null,
  joints: [],
  error: null,
} as const satisfies Partial<FleetArm>;

const blank = (id: string): FleetArm => ({
  id,
  online: null,
  profileName: null,
  title: null,
  ...NO_SUMMARY,
  warnings: {},
});

export function reduceFleet(state: FleetState, ev: FleetEvent): FleetState {
  if (!isValidArmId(ev.id)) return state;
  const prev = state.get(ev.id);
  const arm = prev ?? blank(ev.id);
  let next: FleetArm;
  switch (ev.kind) {
    case 'online': {
      const t = ev.text.trim();
      const online = t === '1' ? true : t === '0' ? false : null;
      if (prev && prev.online === online) return state;
      next = { ...arm, online };
      break;
    }
    case 'profile':
      if (prev && prev.profileName === ev.name && prev.title === ev.title) return state;
      next = { ...arm, profileName: ev.name, title: ev.title };
      break;
    case 'summary': {
      const s = ev.summary;
      next = s
        ? {
            ...arm,
            level: s.health,
            alarm: s.alarm,
            state: s.state,
            why: s.why,
            holder: s.holder,
            joints: s.joints,
            error: s.error,
          }
        : { ...arm, ...NO_SUMMARY };
      break;
    }
    case 'alert': {
      const warnings = { ...arm.warnings };
      if (ev.alert.kind === 'thermal-warning') warnings[ev.alert.id] = ev.alert.detail;
      else if (ev.alert.id in warnings) delete warnings[ev.alert.id];
      else return state;
      next = { ...arm, warnings };
      break;
    }
  }
  const out = new Map(state);
  out.set(ev.id, next);
  return out;
}

const sameJoints = (a: readonly SummaryJoint[], b: readonly SummaryJoint[]) =>
  a.length === b.length && a.every((j, i) => j.deg === b[i]!.deg && j.id === b[i]!.id);

/** Whether two arms look the same in the fleet list (their pose included). */
export const sameSummary = (a: FleetArm | undefined, b: FleetArm | undefined): boolean =>
  a !== undefined &&
  b !== undefined &&
  a.online === b.online &&
  a.profileName === b.profileName &&
  a.title === b.title &&
  a.level === b.level &&
  a.alarm === b.alarm &&
  a.state === b.state &&
  a.why === b.why &&
  a.holder === b.holder &&
  a.error?.t === b.error?.t &&
  a.warnings === b.warnings &&
  sameJoints(a.joints, b.joints);

const byId = new Intl.Collator('en', { numeric: true });

/**
 * The arms, online ones first, then by id, numbers in ids as numbers (arm2 before arm10; a broker
 * remembers every arm it has seen).
 */
export const fleetList = (state: FleetState): FleetArm[] =>
  [...state.values()].sort(
    (a, b) => Number(b.online === true) - Number(a.online === true) || byId.compare(a.id, b.id),
  );
