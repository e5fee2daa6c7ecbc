/**
 * The round-trip baseline: a bare mqtt.js client that republishes every message it gets on
 * `<in>` to `<out>` unchanged — the same subscription QoS (`CLEAN_SESSION_SUBSCRIBE_QOS`, 0) and publish
 * QoS (0) as the simulator's control → status path, and nothing else. Prints `{"ready":true}` once subscribed.
 * Usage: echo.ts <mqtt url> <in topic> <out topic> <max seconds>
 */
import mqtt from 'mqtt';
import { CLEAN_SESSION_SUBSCRIBE_QOS } from '@armtwin/protocol';

const [url = '', topicIn = '', topicOut = '', maxS = '600'] = process.argv.slice(2);
const client = await mqtt.connectAsync(url, { clientId: `bench-echo-${process.pid}`, clean: true });
client.on('message', (_topic, payload) => client.publish(topicOut, payload, { qos: 0 }));
await client.subscribeAsync(topicIn, { qos: CLEAN_SESSION_SUBSCRIBE_QOS });
process.stdout.write(`${JSON.stringify({ ready: true })}\n`);
const stop = () => {
  void client.endAsync().finally(() => process.exit(0));
};
setTimeout(stop, Number(maxS) * 1000).unref();
process.once('SIGTERM', stop);
process.once('SIGINT', stop);
