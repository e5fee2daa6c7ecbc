/**
 * Watching an MQTT topic from a fresh subscriber in a Vitest file (what a newcomer sees,
 * retained messages first); every subscriber is ended in afterAll.
 */
import mqtt, { type MqttClient } from 'mqtt';
import { afterAll } from 'vitest';

/** `watch(topic)`: the payloads on `topic` as they come, from a fresh subscriber of `brokerUrl()`. */
export function useTopicWatch(brokerUrl: () => string): (topic: string) => Promise<Buffer[]> {
  const clients: MqttClient[] = [];
  afterAll(async () => {
    await Promise.all(clients.map((c) => c.endAsync(true)));
  });
  return async (topic) => {
    const client = await mqtt.connectAsync(brokerUrl(), { reconnectPeriod: 0 });
    clients.push(client);
    const seen: Buffer[] = [];
    client.on('message', (t, payload) => t === topic && seen.push(payload));
    await client.subscribeAsync(topic, { qos: 1 });
    return seen;
  };
}
