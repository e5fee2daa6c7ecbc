/**
 * `@foxglove/ws-protocol`'s classes as Node loads the package: its CommonJS build (`main`) names
 * them only on its default export, its ES build (`module`, what bundlers and types read) as named
 * exports. Either way, the same class.
 */
import * as wsProtocol from '@foxglove/ws-protocol';

type Module = typeof wsProtocol;
const mod: Module = (wsProtocol as Module & { default?: Module }).default ?? wsProtocol;

export const FoxgloveServer = mod.FoxgloveServer;
export type FoxgloveServer = wsProtocol.FoxgloveServer;
export const FoxgloveClient = mod.FoxgloveClient;
export type FoxgloveClient = wsProtocol.FoxgloveClient;
