/**
 * `armtwin up --foxglove [PORT]`: the live Foxglove WebSocket server (@armtwin/foxglove) on the
 * embedded broker, in-process: it watches as a viewer does, reads the control topics as the
 * middleware does (for the commanded targets), and sends each Foxglove user's commands as that
 * user, so the broker's roles and the controller's lease apply as to the HUD.
 */
import type { Principal } from '@armtwin/auth';
import type { Broker, BrokerTls } from '@armtwin/broker';
import { startFoxgloveServer, type ArmtwinFoxglove } from '@armtwin/foxglove';
import { linkOptions } from '@armtwin/protocol';

export interface FoxglovePartOptions {
  broker: Broker;
  port: number;
  host: string;
  tls: BrokerTls | null;
  modelDirs: readonly string[];
  onFirst: (kind: string, message: string) => void;
}

export async function startFoxglovePart(o: FoxglovePartOptions): Promise<ArmtwinFoxglove> {
  let n = 0;
  const connect = (who: Principal) =>
    o.broker.connectInProcess(who, {
      clientId: `armtwin-foxglove-${who.name}-${++n}`,
      ...linkOptions(),
    });
  const watch = connect({ name: 'foxglove', role: 'viewer' });
  const control = connect({ name: 'foxglove', role: 'middleware' });
  try {
    return await startFoxgloveServer({
      port: o.port,
      host: o.host,
      tls: o.tls,
      logins: o.broker.logins,
      modelDirs: o.modelDirs,
      watch,
      control,
      connectAs: connect,
      onFirst: o.onFirst,
    }).then((server) => ({
      ...server,
      async stop() {
        await server.stop();
        await Promise.all([watch.endAsync(), control.endAsync()]);
      },
    }));
  } catch (err) {
    await Promise.all([watch.endAsync(), control.endAsync()]);
    throw err;
  }
}
