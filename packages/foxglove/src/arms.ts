/**
 * The arms the Foxglove server shows: every arm that announces its profile (retained
 * `arm/{id}/profile`) whose robot folder is found gets its channels (./channels.ts) and its
 * services (`/{arm}/stop`, `/take`, `/release`) advertised; an empty announcement removes them.
 * Its MQTT traffic goes through its ArmFeed to the channels' subscribers, encoded only while a
 * client subscribes. Holder records go to the caller (for the sessions' claims).
 */
import fs from 'node:fs';
import path from 'node:path';
import type { MqttClient } from 'mqtt';
import type { FoxgloveServer } from '@foxglove/ws-protocol';
import { PROFILE_NAME, readRobotFolder, type RobotFolder } from '@armtwin/motion/robot-folder';
import {
  allArmsTopic,
  CLEAN_SESSION_SUBSCRIBE_QOS,
  holderTopic,
  isValidArmId,
  parseHolder,
  parseTopic,
  type HolderRecord,
} from '@armtwin/protocol';
import { parseAnnouncement, parseUrdfJoints } from '@armtwin/robot';
import { armChannels, LATCHED } from './channels.ts';
import type { ChannelKind } from './topics.ts';
import { ArmFeed } from './arm-feed.ts';
import { urdfWithPackagePaths } from './robot-assets.ts';

export const ARM_SERVICES = ['stop', 'take', 'release'] as const;
export type ArmService = (typeof ARM_SERVICES)[number];

export interface Arm {
  id: string;
  folder: RobotFolder;
  feed: ArmFeed;
  channels: Map<ChannelKind, number>;
  services: Map<number, ArmService>;
  /** The latched messages' payloads, by channel id. */
  latched: Map<number, Uint8Array>;
}

const EMPTY_SCHEMA = {
  encoding: 'json',
  schemaName: 'std_srvs/Empty',
  schemaEncoding: 'jsonschema',
  schema: JSON.stringify({ type: 'object', properties: {} }),
};
const RESULT_SCHEMA = {
  ...EMPTY_SCHEMA,
  schemaName: 'std_srvs/Trigger_Response',
  schema: JSON.stringify({
    type: 'object',
    properties: { success: { type: 'boolean' }, message: { type: 'string' } },
  }),
};

export interface ArmRegistryOptions {
  fox: FoxgloveServer;
  /** Reads what a viewer may: profiles, holders, status, audit, alerts. */
  mqtt: MqttClient;
  /** Reads the control topics (for the targets channel); absent: no targets. */
  control?: MqttClient;
  modelDirs: readonly string[];
  now: () => number;
  onHolder: (armId: string, record: HolderRecord) => void;
  onFirst: (kind: string, message: string) => void;
}

export class ArmRegistry {
  readonly arms = new Map<string, Arm>();
  /** Channels some client subscribes to. */
  private readonly subscribed = new Set<number>();
  private readonly encoder = new TextEncoder();
  /** MQTT messages turned into Foxglove messages, and those sent. */
  readonly counts = { mqttIn: 0, sent: 0, badAnnouncement: 0 };

  constructor(private readonly o: ArmRegistryOptions) {
    o.fox.on('subscribe', (id) => this.subscribed.add(id));
    o.fox.on('unsubscribe', (id) => this.subscribed.delete(id));
    o.mqtt.on('message', (t, payload) => this.onMessage(t, payload));
    if (o.control && o.control !== o.mqtt)
      o.control.on('message', (t, payload) => this.onMessage(t, payload));
    const subscribe = () =>
      o.mqtt.subscribe(
        [allArmsTopic('profile'), 'arm/+/holder'],
        { qos: CLEAN_SESSION_SUBSCRIBE_QOS },
        (err) => {
          if (err) o.onFirst('subscribe', `arm profiles not followed: ${err.message}`);
        },
      );
    o.mqtt.on('connect', subscribe);
    if (o.mqtt.connected) subscribe();
  }

  /** A latched channel's last message (the robot description), if `channelId` is one. */
  latched(channelId: number): Uint8Array | undefined {
    for (const arm of this.arms.values()) {
      const payload = arm.latched.get(channelId);
      if (payload) return payload;
    }
    return undefined;
  }

  /** The arm and service a service id names. */
  service(id: number): { arm: Arm; service: ArmService } | undefined {
    for (const arm of this.arms.values()) {
      const service = arm.services.get(id);
      if (service) return { arm, service };
    }
    return undefined;
  }

  private onMessage(t: string, payload: Buffer): void {
    const parsed = parseTopic(t);
    if (parsed?.kind === 'profile') return this.onAnnouncement(parsed.armId, payload);
    const armId = t.split('/')[1] ?? '';
    if (!isValidArmId(armId)) return;
    if (t === holderTopic(armId)) {
      const record = parseHolder(payload);
      if (record) this.o.onHolder(armId, record);
      return;
    }
    const arm = this.arms.get(armId);
    if (!arm) return;
    this.counts.mqttIn++;
    for (const m of arm.feed.feed(t, payload, this.o.now())) {
      const id = arm.channels.get(m.kind)!;
      if (!this.subscribed.has(id)) continue;
      this.o.fox.sendMessage(id, m.ns, this.encoder.encode(JSON.stringify(m.body)));
      this.counts.sent++;
    }
  }

  private onAnnouncement(armId: string, payload: Buffer): void {
    const text = payload.toString('utf8');
    const name = text === '' ? '' : announcedName(text);
    const known = this.arms.get(armId);
    if (known && known.folder.profile.name === name) return;
    if (known) this.remove(known);
    if (!name) {
      if (text !== '') this.counts.badAnnouncement++;
      return;
    }
    try {
      this.add(armId, name);
    } catch (err) {
      this.o.onFirst(`arm:${armId}`, `arm ${armId} not shown: ${(err as Error).message}`);
    }
  }

  private add(armId: string, name: string): void {
    const dir =
      this.o.modelDirs.find((d) => fs.existsSync(path.join(d, name, 'profile.json'))) ??
      this.o.modelDirs.at(-1)!;
    const folder = readRobotFolder(name, dir);
    const urdf = fs.readFileSync(path.join(dir, name, folder.profile.urdf), 'utf8');
    const joints = parseUrdfJoints(urdf);
    if (!joints.ok) throw new Error(`its URDF: ${joints.errors.join('; ')}`);
    const fox = this.o.fox;
    const arm: Arm = {
      id: armId,
      folder,
      feed: new ArmFeed(armId, folder.profile, joints.joints),
      channels: new Map(),
      services: new Map(),
      latched: new Map(),
    };
    for (const { kind, spec } of armChannels(armId)) {
      const id = fox.addChannel(spec);
      arm.channels.set(kind, id);
      if (LATCHED.has(kind))
        arm.latched.set(
          id,
          this.encoder.encode(JSON.stringify({ data: urdfWithPackagePaths(urdf, name) })),
        );
    }
    for (const service of ARM_SERVICES) {
      const id = fox.addService({
        name: `/${armId}/${service}`,
        type: 'std_srvs/Trigger',
        request: EMPTY_SCHEMA,
        response: RESULT_SCHEMA,
      });
      arm.services.set(id, service);
    }
    this.arms.set(armId, arm);
    this.o.mqtt.subscribe(arm.feed.topics, { qos: 0 });
    this.o.control?.subscribe(arm.feed.controlTopics, { qos: 0 });
  }

  private remove(arm: Arm): void {
    this.o.mqtt.unsubscribe(arm.feed.topics);
    this.o.control?.unsubscribe(arm.feed.controlTopics);
    for (const id of arm.channels.values()) {
      this.o.fox.removeChannel(id);
      this.subscribed.delete(id);
    }
    for (const id of arm.services.keys()) this.o.fox.removeService(id);
    this.arms.delete(arm.id);
  }
}

/** The profile name of an announcement, or '' when it has none a robot folder could have. */
function announcedName(text: string): string {
  if (!parseAnnouncement(text).ok) return '';
  const name = (JSON.parse(text) as { name?: unknown }).name;
  return typeof name === 'string' && PROFILE_NAME.test(name) ? name : '';
}
