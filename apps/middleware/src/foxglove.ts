/**
 * The live Foxglove server in the middleware (`FOXGLOVE_PORT`, docs/foxglove.md), for
 * deployments without `armtwin up`: the same server as `armtwin up --foxglove`
 * (@armtwin/foxglove), on the broker(s) of MQTT_URL.
 *
 * - It watches with the middleware's own account (MQTT_USERNAME, the `middleware` role: status,
 *   control for the targets, audit, profiles, holders, alerts, cameras), on a connection of its
 *   own (`<MQTT_CLIENT_ID>-foxglove`, a clean session: it never holds up the stored stream).
 * - Log-ins are the HTTP API's (ARMTWIN_USERS); a client's commands go to the broker under that
 *   user's own name and the password it logged in with, so the broker's roles, the lease and
 *   the controller decide, as for the HUD. Without a users file it is the anonymous local demo:
 *   loopback only, each client's commands anonymous on the broker under a `foxglove-N` topic.
 */
import { startFoxgloveServer, type ArmtwinFoxglove } from '@armtwin/foxglove';
import type { LoginThrottle } from '@armtwin/auth';
import { connectBrokers, parseBrokerList } from '@armtwin/link';
import { linkOptions } from '@armtwin/protocol';
import type { MiddlewareConfig } from './config.ts';

export interface MiddlewareFoxgloveOptions {
  config: MiddlewareConfig;
  port: number;
  logins: LoginThrottle | null;
  modelDirs: readonly string[];
  onFirst: (kind: string, message: string) => void;
}

export async function startMiddlewareFoxglove(
  o: MiddlewareFoxgloveOptions,
): Promise<ArmtwinFoxglove> {
  const { config } = o;
  const urls = parseBrokerList(config.mqttUrl);
  const link = linkOptions({
    keepalive: config.mqttKeepaliveS,
    reconnectPeriod: config.mqttReconnectMs,
  });
  let n = 0;
  const connect = (clientId: string, username: string, password: string | null) =>
    connectBrokers(urls, {
      ...link,
      clientId,
      clean: true,
      protocolVersion: 4,
      ...(username ? { username, password: password ?? '' } : {}),
    });
  const watch = connect(
    `${config.mqttClientId}-foxglove`,
    config.mqttUsername,
    config.mqttPassword,
  );
  try {
    const server = await startFoxgloveServer({
      port: o.port,
      host: config.host,
      tls: null,
      logins: o.logins,
      modelDirs: o.modelDirs,
      watch,
      control: watch,
      connectAs: (who, password) =>
        connect(
          `armtwin-foxglove-${who.name}-${++n}`,
          o.logins ? who.name : '',
          o.logins ? password : null,
        ),
      onFirst: o.onFirst,
    });
    return {
      ...server,
      async stop() {
        await server.stop();
        await watch.endAsync();
      },
    };
  } catch (err) {
    await watch.endAsync();
    throw err;
  }
}
