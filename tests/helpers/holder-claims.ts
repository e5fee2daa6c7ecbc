/**
 * Taking arms for a user over MQTT the way a page does on a busy cluster: a claim sent before
 * an arm's claim subscription is made (a busy cluster makes one JetStream consumer per QoS 1
 * subscription) reaches nobody, so the user asks again while the arm's live summary (2 Hz), sent
 * well after her last ask, still names nobody. Never once it names her: a second `take` from the
 * holder is a beat, and 2.5 s without one would lose her the arm (docs/protocol.md § Control).
 */
import type { BrokerClient } from '@armtwin/link';
import { parseSummary } from '@armtwin/protocol';
import { until } from './until.ts';

/** Claims each of `arms` for `user` through `client` until every arm's summary names her. */
export async function claimUntilHeld(
  client: BrokerClient,
  user: string,
  arms: readonly string[],
  ms: number,
): Promise<void> {
  const held = new Map<string, { holder: string | null; at: number }>();
  client.on('message', (t, p) => {
    const s = parseSummary(p);
    if (s.ok) held.set(t.split('/')[1]!, { holder: s.summary.holder, at: Date.now() });
  });
  client.subscribe(
    arms.map((arm) => `arm/${arm}/summary`),
    { qos: 0 },
  ); // again at each connect
  const asked = new Map<string, number>();
  await until(
    async () => {
      for (const arm of arms) {
        const h = held.get(arm);
        if (h?.holder === user || (h?.at ?? 0) < (asked.get(arm) ?? 0) + 1500) continue;
        asked.set(arm, Date.now());
        await client.publishAsync(`arm/${arm}/claim/${user}`, 'take', { qos: 1 });
      }
      return arms.every((arm) => held.get(arm)?.holder === user);
    },
    ms,
    `${user} holding ${arms.join(' and ')}`,
    200,
  );
}
