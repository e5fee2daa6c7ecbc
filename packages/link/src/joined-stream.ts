/**
 * A QoS 1 report stream with one message unacknowledged at a time: what is handed in while a
 * message waits for its acknowledgement is joined into the next message.
 *
 * Why: a NATS node stores a QoS 1 PUBLISH in JetStream (replicated) before it acknowledges it,
 * and handles one such PUBLISH of a connection at a time (nats-server `server/mqtt.go`:
 * `mqttProcessPub` → `jsa.storeMsg`, in the connection's read loop). One connection thus gets
 * at most one message per store latency through. An arm sending a 50 Hz stream one report per
 * message falls behind as soon as a store takes over 20 ms (on a loaded cluster: 50–160 ms),
 * and its backlog, its pings' answers behind it, grows without end (docs/cluster.md). Joined,
 * each message carries what came during one round trip: the stream keeps up whatever the
 * latency, and nothing is dropped or reordered.
 *
 * Joining keeps the contract: a status payload is frames, each group after its own `$TIM`, and a
 * payload may already carry several (the simulator's catch-up); two payloads each starting with
 * `$TIM` joined end to end are such a payload. A joined message never exceeds `maxBytes`; once
 * full, the next one starts (a long loss of the broker fills several, sent one after another).
 * Payloads are joined in order, and a message is handed on only after the one before it was
 * settled (acknowledged, or given up by the client, which then reports its own error).
 * Before a client ends, `flushJoined` hands it every waiting message at once (as before joining:
 * an ending mqtt.js client still sends what it holds, and refuses new publishes).
 */
import type { MqttClient } from 'mqtt';

/**
 * A joined message's largest size: 16 KiB, about 200 six-servo reports (4 s at 50 Hz), well
 * under any part's packet limit (MAX_PAYLOAD_BYTES of @armtwin/protocol).
 */
export const JOINED_MAX_BYTES = 16_384;

/** Hands one message to the client; `settled` once it is acknowledged or given up. */
export type SendOne = (payload: Buffer, settled: () => void) => void;

export interface JoinedStream {
  /** Sends `payload` now, or joins it to the next message while one is unacknowledged. */
  send(payload: Buffer): void;
  /** Payloads waiting to go, joined into this many messages (0 while none waits). */
  readonly waiting: number;
  /** Messages handed to the client so far. */
  readonly sent: number;
  /** Hands every waiting message to the client now, without waiting for acknowledgements. */
  flush(): void;
}

export function joinedStream(sendOne: SendOne, maxBytes = JOINED_MAX_BYTES): JoinedStream {
  /** Messages waiting, each a list of payloads whose total is ≤ maxBytes. */
  const queue: { parts: Buffer[]; bytes: number }[] = [];
  let inFlight = false;
  let sent = 0;

  const next = () => {
    const m = queue.shift();
    if (!m) {
      inFlight = false;
      return;
    }
    inFlight = true;
    sent++;
    sendOne(m.parts.length === 1 ? m.parts[0]! : Buffer.concat(m.parts, m.bytes), next);
  };

  return {
    send(payload) {
      const last = queue.at(-1);
      if (last && last.bytes + payload.length <= maxBytes) {
        last.parts.push(payload);
        last.bytes += payload.length;
      } else queue.push({ parts: [payload], bytes: payload.length });
      if (!inFlight) next();
    },
    get waiting() {
      return queue.length;
    },
    get sent() {
      return sent;
    },
    flush() {
      for (let m = queue.shift(); m; m = queue.shift()) {
        sent++;
        sendOne(Buffer.concat(m.parts, m.bytes), () => {});
      }
    },
  };
}

const ofClient = new WeakMap<MqttClient, JoinedStream[]>();

/** A joined QoS 1 stream of `client` on `topic`, flushed by `flushJoined(client)`. */
export function clientJoinedStream(client: MqttClient, topic: string): JoinedStream {
  const s = joinedStream((p, settled) => client.publish(topic, p, { qos: 1 }, () => settled()));
  ofClient.set(client, [...(ofClient.get(client) ?? []), s]);
  return s;
}

/** Hands every waiting message of `client`'s joined streams to it: call it before ending it. */
export function flushJoined(client: MqttClient): void {
  for (const s of ofClient.get(client) ?? []) s.flush();
}
