/**
 * The ingest load: publishes pre-built 6-servo state groups (`$TIM:t!{#000Pp!…#005Pp!}`, one
 * per message, stamps t0, t0+1, … ms) at `rate` messages/s for `seconds`, paced against
 * absolute time in 5 ms ticks, then disconnects cleanly and prints
 * `{"sent":…,"wallS":…,"rate":…}`. A separate process, so the middleware's CPU is its own.
 * With `frame`, each message is one stamped frame instead (`$TIM:t!#00iPp!`, servo i = k mod 6,
 * t = t0 + ⌊k/6⌋ ms: every servo's series gets distinct times), a shape Telegraf can parse too.
 * Usage: publisher.ts <mqtt url> <topic> <rate> <seconds> <t0 ms> <qos> [group|frame]
 *
 * At QoS 0 (no acknowledgement, no state) the PUBLISH packets are encoded ahead, before the
 * clock starts, by mqtt-packet (the encoder mqtt.js itself uses) into one buffer, and each tick
 * writes the due ones to the connection's socket in one write: mqtt.js's own work per message
 * (~10 µs) made this process, on the same two cores as the consumers, the first to saturate
 * (BENCHMARKS.md §2, §8). A tick writes only while the socket is not behind (no pending drain),
 * so `sent` counts what the broker's connection took, not what waits in this process.
 */
import mqtt from 'mqtt';
import mqttPacket from 'mqtt-packet';

const [
  url = '',
  topic = '',
  rateS = '100',
  secondsS = '5',
  t0S = '0',
  qosS = '0',
  shape = 'group',
] = process.argv.slice(2);
const rate = Number(rateS);
const total = Math.max(1, Math.round(rate * Number(secondsS)));
const t0 = Number(t0S);
const qos = Number(qosS) === 1 ? 1 : 0;

const payloads: Buffer[] = new Array(total);
for (let k = 0; k < total; k++) {
  if (shape === 'frame') {
    const id = k % 6;
    const pwm = 1000 + ((Math.floor(k / 6) * 7 + id * 150) % 1000);
    payloads[k] = Buffer.from(`$TIM:${t0 + Math.floor(k / 6)}!#00${id}P${pwm}!`, 'latin1');
    continue;
  }
  let g = '';
  for (let id = 0; id < 6; id++) g += `#00${id}P${1000 + ((k * 7 + id * 150) % 1000)}!`;
  payloads[k] = Buffer.from(`$TIM:${t0 + k}!{${g}}`, 'latin1');
}

/** QoS 0: every packet encoded ahead, back to back; packet k is bytes offsets[k]…offsets[k+1]. */
let wire: { bytes: Buffer; offsets: Float64Array } | null = null;
if (qos === 0) {
  const packets = payloads.map((payload) =>
    mqttPacket.generate({ cmd: 'publish', topic, payload, qos: 0, dup: false, retain: false }),
  );
  const offsets = new Float64Array(total + 1);
  for (let k = 0; k < total; k++) offsets[k + 1] = offsets[k]! + packets[k]!.length;
  wire = { bytes: Buffer.concat(packets, offsets[total]), offsets };
}

const client = await mqtt.connectAsync(url, {
  clientId: `bench-pub-${process.pid}`,
  clean: true,
  reconnectPeriod: 0,
});
const socket = client.stream as unknown as NodeJS.WritableStream & { writableNeedDrain: boolean };
const start = performance.now();
const deadline = start + Number(secondsS) * 1000 * 3 + 10_000; // bounded even when slow
let sent = 0;
await new Promise<void>((resolve) => {
  const tick = () => {
    const now = performance.now();
    const due = Math.min(total, Math.floor(((now - start) * rate) / 1000) + 1);
    if (wire && sent < due && !socket.writableNeedDrain) {
      socket.write(wire.bytes.subarray(wire.offsets[sent], wire.offsets[due]));
      sent = due;
    } else if (!wire) while (sent < due) client.publish(topic, payloads[sent++]!, { qos });
    if (sent >= total || now > deadline) return resolve();
    setTimeout(tick, 5);
  };
  tick();
});
const sendMs = performance.now() - start;
await client.endAsync(); // flushes what is still buffered
const wallMs = performance.now() - start;
process.stdout.write(
  `${JSON.stringify({ sent, wanted: total, sendS: sendMs / 1000, wallS: wallMs / 1000, rate: sent / (wallMs / 1000) })}\n`,
);
process.exit(0);
