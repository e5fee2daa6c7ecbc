/**
 * Puts what an mqtt.js client has written onto its WebSocket now. mqtt-packet corks the client's
 * stream for each packet and uncorks it on `process.nextTick`, which mqtt.js's browser bundle
 * runs as a `setTimeout(…, 0)`: a task that waits behind the page's next frame (rAF and paint
 * run first). For the emergency stop that is a frame too long, so the stop's publish is followed
 * by this, which uncorks at once: `socket.send` runs inside the click or key handler itself.
 * The later nextTick uncork then finds nothing corked and does nothing.
 */

/** The part of a Node-style writable stream this needs (mqtt.js's `client.stream`). */
interface Corkable {
  writableCorked?: number;
  uncork?: () => void;
}

/** Uncorks `client.stream` (if it has one) until nothing is held back. Never throws. */
export function flushNow(client: unknown): void {
  const stream = (client as { stream?: Corkable } | null)?.stream;
  if (!stream || typeof stream.uncork !== 'function') return;
  try {
    // `writableCorked` counts nested corks; bounded in case a stream never reports 0.
    for (let i = 0; i < 8 && (stream.writableCorked ?? 0) > 0; i++) stream.uncork();
  } catch {
    // A closing socket: the packet stays in mqtt.js's outgoing store and is resent on reconnect.
  }
}
