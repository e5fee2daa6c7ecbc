/**
 * Latched channels (the robot description): each client's own `subscribe`
 * (./client-subscriptions.ts) is sent the channel's last message at once, so a Foxglove that
 * connects late still gets the URDF. The message is the protocol's binary Message Data
 * (opcode 1, subscription id, ns, payload).
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

/** Sends a latched channel's last message to a new subscription of `ws`. */
export function sendLatched(
  ws: WebSocket,
  registry: ArmRegistry,
  subId: number,
  channelId: number,
  ns: bigint,
): void {
  const payload = registry.latched(channelId);
  if (payload) ws.send(messageData(subId, ns, payload));
}
