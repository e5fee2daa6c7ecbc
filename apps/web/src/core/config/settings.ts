/**
 * Connection and HUD settings, declared once. Defaults work with `npm start` (the HUD and the
 * broker's MQTT-over-WebSockets on one origin, at /mqtt). The URL query overrides them, e.g.
 * `?broker=ws://127.0.0.1:9001&arm=arm1&alpha=1.5`; the Connection panel saves the rest in
 * localStorage (never the password). Pure apart from `loadSettings`/`saveSettings`.
 */
import { DEMO_ARM_ID, isValidArmId } from '@armtwin/protocol';
import { parseBrokerList } from '@armtwin/link';
import { isTwinMode, type TwinMode } from '../store/TwinPredictor.ts';

export interface HudSettings {
  /**
   * Broker WebSocket URL (`ws://…/mqtt` or `wss://…/mqtt`), or an ordered comma-separated list
   * of them: the first preferred, the others fall-backs (docs/protocol.md § Several brokers).
   */
  brokerUrl: string;
  /** Which arm: `arm/{armId}/…`. */
  armId: string;
  username: string;
  password: string;
  /** The seed's interpolation factor α (t = clamp01((now − start)·α / duration)). */
  interpolationAlpha: number;
  /**
   * How the arm is drawn (`?twin=`): `predict` (where it is now, from its reports, their time
   * stamps and what was commanded; says "Predicted" while ahead of the reports), `interpolate`
   * (the seed's tween toward each report) or `newest` (each report as it came).
   */
  twinMode: TwinMode;
  /** `tttt` of a jog move, ms. */
  jogMoveMs: number;
  /** Shortest time between two jog moves of one servo, ms (50 → at most 20/s). */
  jogIntervalMs: number;
  /** `t` of a Cartesian `$KMS` move, ms. */
  kmsMoveMs: number;
  /** How often to send `$PNG`, ms. */
  pingIntervalMs: number;
  /** Base URL of the middleware's HTTP API (`…/history/series` etc.); `npm start` serves `/api`. */
  apiBase: string;
  /**
   * MQTT keep-alive of an operator's page, s: the deadman's last will fires within 1.5 × this
   * after the page drops (on the embedded broker). Viewers keep the contract's 60 s.
   */
  deadmanKeepAliveS: number;
  /**
   * What the user says their role is, used only when `/api/whoami` cannot answer (a Mosquitto
   * deployment without `npm start`); '' = unknown, treated as viewer (src/core/auth/roles.ts).
   */
  roleHint: '' | 'viewer' | 'operator';
}

/** Same-origin broker URL: ws(s)://<host>/mqtt. */
export function sameOriginBrokerUrl(loc: { protocol: string; host: string }): string {
  return `${loc.protocol === 'https:' ? 'wss' : 'ws'}://${loc.host}/mqtt`;
}

export function defaultSettings(loc: { protocol: string; host: string }): HudSettings {
  return {
    brokerUrl: sameOriginBrokerUrl(loc),
    armId: DEMO_ARM_ID,
    username: '',
    password: '',
    interpolationAlpha: 1,
    twinMode: 'predict',
    jogMoveMs: 100,
    jogIntervalMs: 50,
    kmsMoveMs: 1500,
    pingIntervalMs: 1000,
    apiBase: `${loc.protocol}//${loc.host}/api`,
    deadmanKeepAliveS: 2,
    roleHint: '',
  };
}

const NUMBER_KEYS = {
  alpha: 'interpolationAlpha',
  jogms: 'jogMoveMs',
  kmsms: 'kmsMoveMs',
  keepalive: 'deadmanKeepAliveS',
} as const;

/**
 * Applies query parameters (broker, api, arm, user, password, role, alpha, twin, jogms, kmsms,
 * keepalive) over `base`. An invalid arm id is ignored here; `armQueryProblem` reports it.
 */
export function applyQuery(base: HudSettings, search: string): HudSettings {
  const q = new URLSearchParams(search);
  const out = { ...base };
  const broker = q.get('broker');
  if (broker && brokerListProblem(broker) === null) out.brokerUrl = broker;
  const api = q.get('api');
  if (api && /^(https?:\/\/|\/)\S*$/.test(api)) out.apiBase = api.replace(/\/+$/, '');
  const arm = q.get('arm');
  if (arm && isValidArmId(arm)) out.armId = arm;
  const user = q.get('user');
  if (user !== null) out.username = user;
  const password = q.get('password');
  if (password !== null) out.password = password;
  const role = q.get('role');
  if (role === 'operator' || role === 'viewer') out.roleHint = role;
  const twin = q.get('twin');
  if (isTwinMode(twin)) out.twinMode = twin;
  for (const [key, field] of Object.entries(NUMBER_KEYS)) {
    const v = Number(q.get(key));
    if (q.has(key) && Number.isFinite(v) && v > 0) out[field] = v;
  }
  return out;
}

/** What is wrong with a broker list (comma-separated ws:// or wss:// URLs), or null. */
export function brokerListProblem(text: string): string | null {
  let urls: string[];
  try {
    urls = parseBrokerList(text);
  } catch (err) {
    return (err as Error).message;
  }
  const bad = urls.find((u) => !/^wss?:\/\/[^\s]+$/.test(u));
  return bad === undefined ? null : `Broker URL must start with ws:// or wss:// (“${bad}”)`;
}

/** Checks what a user typed; returns an error message or null. */
export function validateSettings(s: HudSettings): string | null {
  const brokers = brokerListProblem(s.brokerUrl);
  if (brokers) return brokers;
  if (!isValidArmId(s.armId)) return 'Arm id must be 1–32 of a–z, 0–9 and -';
  return null;
}

const STORAGE_KEY = 'armtwin.hud.settings';
type Saved = Pick<HudSettings, 'brokerUrl' | 'armId' | 'username' | 'twinMode'>;

/** Defaults, then what the Connection panel saved, then the URL query. */
export function loadSettings(): HudSettings {
  let settings = defaultSettings(window.location);
  try {
    const saved = JSON.parse(
      window.localStorage.getItem(STORAGE_KEY) ?? 'null',
    ) as Partial<Saved> | null;
    if (saved) settings = { ...settings, ...pick(saved) };
  } catch {
    // unreadable storage: defaults
  }
  return applyQuery(settings, window.location.search);
}

export function saveSettings(s: HudSettings): void {
  try {
    const saved: Saved = {
      brokerUrl: s.brokerUrl,
      armId: s.armId,
      username: s.username,
      twinMode: s.twinMode,
    };
    window.localStorage.setItem(STORAGE_KEY, JSON.stringify(saved));
  } catch {
    // private mode: not saved
  }
}

function pick(s: Partial<Saved>): Partial<Saved> {
  const out: Partial<Saved> = {};
  if (typeof s.brokerUrl === 'string') out.brokerUrl = s.brokerUrl;
  if (typeof s.armId === 'string' && isValidArmId(s.armId)) out.armId = s.armId;
  if (typeof s.username === 'string') out.username = s.username;
  if (isTwinMode(s.twinMode)) out.twinMode = s.twinMode;
  return out;
}
