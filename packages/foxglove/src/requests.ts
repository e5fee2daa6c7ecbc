/**
 * The Foxglove server's answers to requests: the arm services (`/{arm}/stop`, anyone who may
 * command; `/{arm}/take`, `/{arm}/release`, an operator's claim), each answered as
 * std_srvs/Trigger (`{success, message}`) or refused with a service call failure; and asset
 * fetches (`package://<profile>/…`, ./robot-assets.ts).
 */
import { BinaryOpcode, FetchAssetStatus, type IWebSocket } from '@foxglove/ws-protocol';
import type { ArmRegistry } from './arms.ts';
import type { FoxgloveServer } from './ws-protocol.ts';
import { fetchRobotAsset } from './robot-assets.ts';
import type { Session } from './session.ts';

export interface ServerCounts {
  /** Clients that connected. */
  clients: number;
  /** Upgrades refused by the log-in step. */
  refusedLogins: number;
  /** Publishes and service calls refused (a viewer's). */
  refused: number;
  /** Publishes that were not a command (unknown topic, bad JSON, a trajectory refused). */
  badCommands: number;
}

export function serveServices(
  fox: FoxgloveServer,
  registry: ArmRegistry,
  sessionOf: (ws: IWebSocket) => Session | undefined,
  counts: ServerCounts,
): void {
  fox.on('serviceCallRequest', (req, connection) => {
    if (!connection) return;
    const fail = (message: string) =>
      fox.sendServiceCallFailure(
        { op: 'serviceCallFailure', serviceId: req.serviceId, callId: req.callId, message },
        connection,
      );
    const session = sessionOf(connection);
    const found = registry.service(req.serviceId);
    if (!session || !found) return fail('no such service');
    const why = session.refusal;
    if (why) {
      counts.refused++;
      return fail(why);
    }
    const { arm, service } = found;
    let message: string;
    switch (service) {
      case 'stop':
        session.stop(arm.id);
        message = `${arm.id}: stop sent (#255PDST!)`;
        break;
      case 'take':
        session.take(arm.id);
        message = `${arm.id}: asked for control as ${session.who.name} (see /${arm.id}/log)`;
        break;
      case 'release':
        session.release(arm.id);
        message = `${arm.id}: released`;
        break;
      default: {
        const never: never = service;
        return never;
      }
    }
    const data = new TextEncoder().encode(JSON.stringify({ success: true, message }));
    fox.sendServiceCallResponse(
      {
        serviceId: req.serviceId,
        callId: req.callId,
        encoding: 'json',
        data: new DataView(data.buffer),
      },
      connection,
    );
  });
}

export function serveAssets(fox: FoxgloveServer, modelDirs: readonly string[]): void {
  fox.on('fetchAsset', ({ uri, requestId }, connection) => {
    if (!connection) return;
    void fetchRobotAsset(uri, modelDirs).then((r) =>
      fox.sendFetchAssetResponse(
        r.ok
          ? {
              op: BinaryOpcode.FETCH_ASSET_RESPONSE,
              requestId,
              status: FetchAssetStatus.SUCCESS,
              data: new DataView(r.data.buffer, r.data.byteOffset, r.data.byteLength),
            }
          : {
              op: BinaryOpcode.FETCH_ASSET_RESPONSE,
              requestId,
              status: FetchAssetStatus.ERROR,
              error: r.error,
            },
        connection,
      ),
    );
  });
}
