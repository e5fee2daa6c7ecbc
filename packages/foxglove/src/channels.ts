/**
 * The Foxglove channels one arm is shown on (`/{arm}/…`), all JSON-encoded with JSON schemas;
 * their names and schemas are ./topics.ts's (shared with the MCAP export). The server advertises
 * each arm's set when the arm announces its profile. Pure.
 */
import { CHANNEL_KINDS, CHANNEL_SCHEMAS, channelTopic, type ChannelKind } from './topics.ts';

/** Channels sent to each new subscriber at once with the last message (as ROS latches them). */
export const LATCHED: ReadonlySet<ChannelKind> = new Set(['robot_description']);

/** A channel as the protocol's `advertise` carries it (less the id the server gives it). */
export interface ChannelSpec {
  topic: string;
  encoding: 'json';
  schemaName: string;
  schema: string;
  schemaEncoding: 'jsonschema';
}

/** Every channel of arm `armId`, in CHANNEL_KINDS order. */
export function armChannels(armId: string): { kind: ChannelKind; spec: ChannelSpec }[] {
  return CHANNEL_KINDS.map((kind) => ({
    kind,
    spec: {
      topic: channelTopic(armId, kind),
      encoding: 'json',
      schemaName: CHANNEL_SCHEMAS[kind].title,
      schema: JSON.stringify(CHANNEL_SCHEMAS[kind]),
      schemaEncoding: 'jsonschema',
    },
  }));
}

/** Epoch ms → the protocol's nanoseconds and a schema's `{sec, nsec}`. */
export function stampOf(ms: number): { ns: bigint; time: { sec: number; nsec: number } } {
  const whole = Math.floor(ms);
  const sec = Math.floor(whole / 1000);
  const nsec = Math.round((ms - sec * 1000) * 1e6);
  return { ns: BigInt(sec) * 1_000_000_000n + BigInt(nsec), time: { sec, nsec } };
}
