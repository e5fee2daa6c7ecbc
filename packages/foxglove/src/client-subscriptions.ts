/**
 * One client's own subscriptions, as it sends them (`subscribe` and `unsubscribe` ops):
 * `FoxgloveServer` tells of a channel's first subscriber and last unsubscriber only, but the
 * latched robot description (./latched.ts) and the camera streams (./cameras.ts) are sent to
 * each subscription on its own. Malformed ops are left to `FoxgloveServer`, which reports them.
 */
import type { WebSocket } from 'ws';

export interface SubscriptionEvents {
  subscribe(subId: number, channelId: number): void;
  unsubscribe(subId: number): void;
}

export function watchSubscriptions(ws: WebSocket, on: SubscriptionEvents): void {
  ws.on('message', (data, isBinary) => {
    if (isBinary) return;
    let m: { op?: unknown; subscriptions?: unknown; subscriptionIds?: unknown };
    try {
      m = JSON.parse(data.toString()) as typeof m;
    } catch {
      return;
    }
    if (m.op === 'subscribe' && Array.isArray(m.subscriptions))
      for (const s of m.subscriptions as { id?: unknown; channelId?: unknown }[]) {
        if (typeof s.id === 'number' && typeof s.channelId === 'number')
          on.subscribe(s.id, s.channelId);
      }
    else if (m.op === 'unsubscribe' && Array.isArray(m.subscriptionIds))
      for (const id of m.subscriptionIds as unknown[])
        if (typeof id === 'number') on.unsubscribe(id);
  });
}
