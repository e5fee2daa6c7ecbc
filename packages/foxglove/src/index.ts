/**
 * @armtwin/foxglove: armtwin's arms live in Foxglove and Lichtblick (docs/foxglove.md): the
 * WebSocket server (./server.ts), its channels (./channels.ts; names and schemas, shared with the MCAP export: ./topics.ts) and what it takes back (./commands.ts).
 */
export * from './server.ts';
export * from './channels.ts';
export * from './topics.ts';
export * from './commands.ts';
export * from './arm-feed.ts';
export * from './robot-assets.ts';
export { messageData } from './latched.ts';
export type { ConnectAs } from './session.ts';
export type { ServerCounts } from './requests.ts';
