/**
 * The connect options of the page's MQTT clients (the arm link and the fleet link), made in one
 * place: the contract's keep-alive, reconnect and connect timeout (`linkOptions()` of
 * `@armtwin/protocol`, §6), the log-in, a fresh client id, a clean session.
 */
import { linkOptions, type LinkOptions } from '@armtwin/protocol';

export interface ConnectOptions extends LinkOptions {
  clientId: string;
  username?: string;
  password?: string;
  clean: boolean;
  /** The deadman's last will (operators only): retained `0` on `arm/{id}/operator`. */
  will?: { topic: string; payload: string; qos: 1; retain: boolean };
}

/** Which of the page's clients: the id's prefix (`armtwin-hud-…`, `armtwin-fleet-…`). */
export type ClientKind = 'hud' | 'fleet';

export function connectOptions(
  kind: ClientKind,
  login: { username: string; password: string },
  overrides: Partial<LinkOptions> = {},
): ConnectOptions {
  return {
    clientId: `armtwin-${kind}-${Math.random().toString(16).slice(2, 10)}`,
    ...(login.username ? { username: login.username } : {}),
    ...(login.password ? { password: login.password } : {}),
    ...linkOptions(overrides),
    clean: true,
  };
}
