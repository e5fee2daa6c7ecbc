/**
 * The fleet: every arm seen on the broker, from the retained `arm/+/online` and `arm/+/profile`
 * and the health reports on `arm/{id}/status`. A pure reducer: each event → a new state (the
 * same object when nothing changed); `sameSummary` tells whether an arm's row looks different.
 */
import {
  isValidArmId,
  temperatureLevel,
  voltageLevel,
  worstLevel,
  type HealthLevel,
} from '@armtwin/protocol';

export interface FleetArm {
  readonly id: string;
  /** Retained `online`: true, false, or null before it is known. */
  readonly online: boolean | null;
  /** From the retained profile: its name and title (null until one is announced). */
  readonly profileName: string | null;
  readonly title: string | null;
  /** Worst health level over the servos' latest reports ('unknown' before any). */
  readonly level: HealthLevel | 'unknown';
  /** One line for the badge's title: which servo, what. Empty when normal. */
  readonly alarm: string;
  /** Latest temperature (°C) and supply (mV) per servo id. */
  readonly health: Readonly<Record<number, { temp: number; mv: number }>>;
}

export type FleetState = ReadonlyMap<string, FleetArm>;

export type FleetEvent =
  | { kind: 'online'; id: string; text: string }
  | { kind: 'profile'; id: string; name: string | null; title: string | null }
  | { kind: 'health'; id: string; servos: readonly { id: number; temp: number; mv: number }[] };

export const EMPTY_FLEET: FleetState = new Map();

const blank = (id: string): FleetArm => ({
  id,
  online: null,
  profileName: null,
  title: null,
  level: 'unknown',
  alarm: '',
  health: {},
});

/** The worst level over servos and the words for it ("servo 002: 78 °C"). */
export function healthSummary(health: FleetArm['health']): {
  level: FleetArm['level'];
  alarm: string;
} {
  let level: FleetArm['level'] = 'unknown';
  const words: string[] = [];
  for (const [key, h] of Object.entries(health)) {
    const parts: string[] = [];
    let servo: FleetArm['level'] = 'unknown';
    if (Number.isFinite(h.temp)) {
      const t = temperatureLevel(h.temp);
      servo = t;
      if (t !== 'normal') parts.push(`${Math.round(h.temp)} °C`);
    }
    if (Number.isFinite(h.mv)) {
      const v = voltageLevel(h.mv / 1000);
      servo = servo === 'unknown' ? v : worstLevel(servo, v);
      if (v !== 'normal') parts.push(`${(h.mv / 1000).toFixed(2)} V`);
    }
    if (servo === 'unknown') continue;
    level = level === 'unknown' ? servo : worstLevel(level, servo);
    if (parts.length > 0) words.push(`servo ${key.padStart(3, '0')}: ${parts.join(', ')}`);
  }
  return { level, alarm: words.join('; ') };
}

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
    case 'health': {
      if (ev.servos.length === 0) return state;
      const health = { ...arm.health };
      for (const s of ev.servos) health[s.id] = { temp: s.temp, mv: s.mv };
      next = { ...arm, health, ...healthSummary(health) };
      break;
    }
  }
  const out = new Map(state);
  out.set(ev.id, next);
  return out;
}

/** Whether two arms look the same in the fleet list (health numbers aside). */
export const sameSummary = (a: FleetArm | undefined, b: FleetArm | undefined): boolean =>
  a !== undefined &&
  b !== undefined &&
  a.online === b.online &&
  a.profileName === b.profileName &&
  a.title === b.title &&
  a.level === b.level &&
  a.alarm === b.alarm;

/** The arms, online ones first, then by id (a broker remembers every arm it has seen). */
export const fleetList = (state: FleetState): FleetArm[] =>
  [...state.values()].sort(
    (a, b) =>
      Number(b.online === true) - Number(a.online === true) ||
      (a.id < b.id ? -1 : a.id > b.id ? 1 : 0),
  );
