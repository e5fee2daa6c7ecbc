/** Who holds an arm, as a fresh MQTT client reads it through a given broker (tests/integration). */
import mqtt from 'mqtt';

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

/**
 * The user holding each of `arms`, as the retained `arm/{id}/holder` a fresh client is sent on
 * subscribing through `url` (undefined: none came within 5 s); rejects when the subscription is
 * refused.
 */
export async function holdersOn(
  url: string,
  arms: string[],
): Promise<(string | null | undefined)[]> {
  const c = await mqtt.connectAsync(url, { clientId: `reader-${Date.now()}`, reconnectPeriod: 0 });
  c.on('error', () => {});
  const seen = new Map<string, string | null>();
  c.on('message', (t, p, packet) => {
    if (packet.retain) seen.set(t, (JSON.parse(p.toString()) as { user: string | null }).user);
  });
  const topics = arms.map((a) => `arm/${a}/holder`);
  try {
    await c.subscribeAsync(topics, { qos: 1 });
  } catch (err) {
    await c.endAsync(true);
    throw err;
  }
  const deadline = Date.now() + 5000;
  while (seen.size < topics.length && Date.now() < deadline) await sleep(100);
  await c.endAsync();
  return topics.map((t) => seen.get(t));
}
