/**
 * The profiles arms announce (retained `arm/{id}/profile`, `{"name", "title", "profile"}`: a
 * sim, a serial or bus gateway) as seen on `armtwin up`'s broker, by arm id: how a model copy
 * of an arm `up` does not simulate (a real one behind a gateway) finds its profile. An empty or
 * unreadable announcement forgets the arm.
 */
import type { MqttClient } from 'mqtt';
import { allArmsTopic, CLEAN_SESSION_SUBSCRIBE_QOS, parseTopic } from '@armtwin/protocol';
import { PROFILE_NAME } from '@armtwin/sim';

export interface AnnouncedProfiles {
  /** The profile name arm `armId` announced last, or undefined. */
  nameOf(armId: string): string | undefined;
  stop(): Promise<void>;
}

/** The `name` of an announcement, or '' when it has none a profile folder could have. */
export function announcedName(payload: string): string {
  try {
    const name = (JSON.parse(payload) as { name?: unknown } | null)?.name;
    return typeof name === 'string' && PROFILE_NAME.test(name) ? name : '';
  } catch {
    return '';
  }
}

/** Follows every arm's announcement with `client` (one that may read `arm/+/profile`). */
export function watchAnnouncedProfiles(
  client: MqttClient,
  onFirst: (kind: string, message: string) => void,
): AnnouncedProfiles {
  const names = new Map<string, string>();
  client.on('message', (topic, payload) => {
    const t = parseTopic(topic);
    if (t?.kind !== 'profile') return;
    const name = announcedName(payload.toString('utf8'));
    if (name) names.set(t.armId, name);
    else names.delete(t.armId);
  });
  const subscribe = () =>
    client.subscribe(allArmsTopic('profile'), { qos: CLEAN_SESSION_SUBSCRIBE_QOS }, (err) => {
      if (err) onFirst('model:subscribe', `arm profiles not followed: ${err.message}`);
    });
  client.on('connect', subscribe);
  if (client.connected) subscribe();
  return {
    nameOf: (armId) => names.get(armId),
    stop: () => client.endAsync().catch(() => {}),
  };
}
