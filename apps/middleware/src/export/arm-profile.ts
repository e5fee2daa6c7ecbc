/**
 * Which robot an arm was, as the arm announced it (retained `arm/{id}/profile`), for an export
 * typed without `--profile`:
 *   1. the history: the last `profile` point the middleware stored for the arm before the
 *      range's end (it stores each announcement it sees, ingest.ts), looked for a year back;
 *   2. else the broker: the arm's retained announcement now (an arm recorded before the
 *      middleware stored announcements, or by a middleware that could not read them).
 * `--profile NAME` overrides both. The name is a robot folder's (`<models>/<name>/`).
 */
import { connect } from 'mqtt';
import { parseAnnouncement } from '@armtwin/robot';
import { parseBrokerList } from '@armtwin/link';
import { PROFILE_NAME } from '@armtwin/motion/robot-folder';
import type { HistoryReader } from '../history/reader.ts';
import { nsFromRfc3339 } from './recording.ts';

/** Where the profile came from (the CLI says so, the MCAP's metadata keeps it). */
export type ProfileSource = 'flag' | 'history' | 'broker';

export interface FoundProfile {
  name: string;
  source: ProfileSource;
}

/** How far back of the range's end the history is searched for an announcement. */
export const PROFILE_LOOKBACK_MS = 366 * 24 * 3600_000;

/** The profile name the arm last announced before `stopMs`, as the middleware stored it. */
export async function storedProfile(
  reader: HistoryReader,
  arm: string,
  stopMs: number,
  lookbackMs = PROFILE_LOOKBACK_MS,
): Promise<string | null> {
  const rows = await reader.measurement('profile', arm, stopMs - lookbackMs, stopMs);
  let last: { ns: bigint; name: string } | null = null;
  for (const r of rows) {
    if (typeof r.name !== 'string' || !PROFILE_NAME.test(r.name)) continue;
    const ns = nsFromRfc3339(String(r._time));
    if (!last || ns >= last.ns) last = { ns, name: r.name };
  }
  return last?.name ?? null;
}

export interface BrokerLogin {
  /** MQTT_URL: one URL or a comma-separated list (the first is asked). */
  url: string;
  username: string;
  password: string;
}

/**
 * The profile name in the arm's retained announcement, or null when there is none, it is not a
 * profile, or the broker does not answer within `timeoutMs`.
 */
export async function announcedProfile(
  login: BrokerLogin,
  arm: string,
  timeoutMs = 3000,
): Promise<string | null> {
  let url: string | undefined;
  try {
    url = parseBrokerList(login.url)[0];
  } catch {
    return null;
  }
  if (!url) return null;
  const client = connect(url, {
    username: login.username || undefined,
    password: login.password || undefined,
    reconnectPeriod: 0,
    connectTimeout: timeoutMs,
  });
  const topic = `arm/${arm}/profile`;
  try {
    return await new Promise<string | null>((resolve) => {
      const timer = setTimeout(() => resolve(null), timeoutMs);
      const done = (name: string | null) => {
        clearTimeout(timer);
        resolve(name);
      };
      client.on('error', () => done(null));
      client.on('message', (t, payload) => {
        if (t !== topic) return;
        const r = parseAnnouncement(payload.toString('utf8'));
        done(r.ok && PROFILE_NAME.test(r.profile.name) ? r.profile.name : null);
      });
      client.on('connect', () => {
        client.subscribe(topic, { qos: 1 }, (err) => err && done(null));
      });
    });
  } finally {
    await client.endAsync(true).catch(() => {});
  }
}
