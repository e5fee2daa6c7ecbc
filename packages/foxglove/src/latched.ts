/**
 * Latched channels (the robot description): `FoxgloveServer` tells of a channel's first
 * subscriber only, so each client's own `subscribe` is watched here, and the channel's last
 * message is sent to that subscription at once: a Foxglove that connects late still gets the URDF.
 * The message is the protocol's binary Message Data (opcode 1, subscription id, ns, payload).
 */
import type { WebSocket } from 'ws';
import type { ArmRegistry } from './arms.ts';

const MESSAGE_DATA = 1;

/** The binary Message Data frame of `payload` for subscription `subId`. */
export function messageData(subId: number, ns: bigint, payload: Uint8Array): Uint8Array {
  const out = new Uint8Array(1 + 4 + 8 + payload.byteLength);
  const view = new DataView(out.buffer);
  view.setUint8(0, MESSAGE_DATA);
  view.setUint32(1, subId, true);
  view.setBigUint64(5, ns, true);
  out.set(payload, 13);
  return out;
}

export function latchedOnSubscribe(
  ws: WebSocket,
  registry: ArmRegistry,
  nowNs: () => bigint,
): void {
  ws.on('message', (data, isBinary) => {
    if (isBinary) return;
    let m: { op?: unknown; subscriptions?: unknown };
    try {
      m = JSON.parse(data.toString()) as typeof m;
    } catch {
      return; // FoxgloveServer reports it
    }
    if (m.op !== 'subscribe' || !Array.isArray(m.subscriptions)) return;
    for (const s of m.subscriptions as { id?: unknown; channelId?: unknown }[]) {
      if (typeof s.id !== 'number' || typeof s.channelId !== 'number') continue;
      const payload = registry.latched(s.channelId);
      if (payload) ws.send(messageData(s.id, nowNs(), payload));
    }
  });
}
