/**
 * The fleet's MQTT edge: one mqtt.js client (injected, like ArmLink's) beside the arm link. It
 * follows every arm on the broker (retained `arm/+/online`, `arm/+/profile`), the health reports
 * of the arms not selected (`arm/{id}/status`, health frames only: the selected arm's come
 * through the store), and the selected arm's motion feedback; it publishes motion requests on
 * `arm/{id}/request`. Plain state, no React: panels sample `state` and `version`.
 */
import {
  allArmsTopic,
  armTopics,
  createReader,
  isValidArmId,
  parseTopic,
  unhandled,
} from '@armtwin/protocol';
import { parseAnnouncement, type Profile } from '@armtwin/robot';
import type { MotionRequest } from '@armtwin/motion';
import { connectOptions, type ConnectOptions } from '../link/connectOptions.ts';
import type { MqttLike } from '../link/MqttLike.ts';
import {
  countDrop,
  emptyDropCounters,
  type DropCounters,
  type FirstErrors,
} from '../store/readerErrors.ts';
import type { HudSettings } from '../config/settings.ts';
import {
  EMPTY_FLEET,
  reduceFleet,
  sameSummary,
  type FleetEvent,
  type FleetState,
} from './fleet.ts';
import { parseFeedback, type Feedback } from './feedback.ts';

export interface FleetMqtt extends MqttLike {
  unsubscribe(topics: string[], cb?: (err?: Error) => void): unknown;
}
export type FleetConnect = (url: string, opts: ConnectOptions) => FleetMqtt;

/** `dropped`, `droppedByKind`: what the reader of the other arms' health reports dropped. */
export interface FleetCounters extends DropCounters {
  messages: number;
  /** Announcements that failed `parseProfile` (the arm keeps its previous profile). */
  badProfiles: number;
  /** Feedback that was not a feedback object. */
  badFeedback: number;
  requests: number;
}

const decoder = new TextDecoder();

export class FleetLink {
  state: FleetState = EMPTY_FLEET;
  /** Bumped when an arm appears or its row changes (online, profile, health level). */
  version = 0;
  /** Parsed profile per arm id, from the retained announcements. */
  readonly profiles = new Map<string, Profile>();
  readonly counters: FleetCounters = {
    messages: 0,
    ...emptyDropCounters(),
    badProfiles: 0,
    badFeedback: 0,
    requests: 0,
  };
  /** First message per reader error kind (Status panel). */
  readonly firstError: FirstErrors = {};
  connected = false;
  lastError = '';
  private client: FleetMqtt | null = null;
  private selected: string;
  private readonly statusSubs = new Set<string>();
  private readonly profileListeners = new Set<(armId: string, profile: Profile) => void>();
  private readonly feedbackListeners = new Set<(f: Feedback) => void>();
  private readonly health: { id: number; temp: number; mv: number }[] = [];
  private readonly reader = createReader({
    onFrame: (f) => {
      if (f.type === 'health') this.health.push({ id: f.id, temp: f.temp, mv: f.mv });
    },
    onGroup: (g) => {
      for (const f of g.frames)
        if (f.type === 'health') this.health.push({ id: f.id, temp: f.temp, mv: f.mv });
    },
    onError: (e) => countDrop(this.counters, this.firstError, e),
  });

  constructor(
    private settings: HudSettings,
    private readonly connect: FleetConnect,
  ) {
    this.selected = settings.armId;
  }

  get selectedArm(): string {
    return this.selected;
  }

  start(): void {
    const s = this.settings;
    const client = this.connect(s.brokerUrl, connectOptions('fleet', s));
    this.client = client;
    client.on('connect', () => {
      this.connected = true;
      this.statusSubs.clear();
      const topics = [
        allArmsTopic('online'),
        allArmsTopic('profile'),
        armTopics(this.selected).feedback,
      ];
      client.subscribe(topics, { qos: 1 }, (err) => {
        if (err) this.lastError = `fleet subscribe failed: ${err.message}`;
      });
      for (const id of this.state.keys()) this.watchStatus(id);
    });
    client.on('close', () => (this.connected = false));
    client.on('error', (err) => (this.lastError = err.message));
    client.on('message', (topic, payload) => this.onMessage(topic, payload));
  }

  stop(): void {
    this.client?.end(true);
    this.client = null;
    this.connected = false;
  }

  /** Follows another arm: its feedback, and the health of the one left goes through the fleet. */
  select(armId: string): void {
    if (!isValidArmId(armId) || armId === this.selected) return;
    const old = this.selected;
    this.selected = armId;
    const c = this.client;
    if (!c) return;
    c.unsubscribe([armTopics(old).feedback]);
    c.subscribe([armTopics(armId).feedback], { qos: 1 });
    if (this.statusSubs.delete(armId)) c.unsubscribe([armTopics(armId).status]);
    if (this.state.has(old)) this.watchStatus(old);
  }

  /**
   * Publishes a motion request to the selected arm (on `topic`: the user's own request topic
   * when it is given, docs/protocol.md § Control); false when not connected.
   */
  request(req: MotionRequest, topic = armTopics(this.selected).request): boolean {
    const c = this.client;
    if (!c || !this.connected) return false;
    this.counters.requests++;
    c.publish(topic, JSON.stringify(req), { qos: 1 }, (err) => {
      if (err) this.lastError = `request not sent: ${err.message}`;
    });
    return true;
  }

  onProfile(fn: (armId: string, profile: Profile) => void): () => void {
    this.profileListeners.add(fn);
    return () => this.profileListeners.delete(fn);
  }

  onFeedback(fn: (f: Feedback) => void): () => void {
    this.feedbackListeners.add(fn);
    return () => this.feedbackListeners.delete(fn);
  }

  private watchStatus(id: string): void {
    if (id === this.selected || this.statusSubs.has(id) || !this.client) return;
    this.statusSubs.add(id);
    this.client.subscribe([armTopics(id).status], { qos: 0 });
  }

  private dispatch(ev: FleetEvent): void {
    const before = this.state.get(ev.id);
    this.state = reduceFleet(this.state, ev);
    const after = this.state.get(ev.id);
    if (!sameSummary(before, after)) this.version++;
    if (!before && after) this.watchStatus(ev.id);
  }

  private onMessage(topic: string, payload: Uint8Array): void {
    this.counters.messages++;
    const p = parseTopic(topic);
    if (!p) return;
    const t = { id: p.armId };
    switch (p.kind) {
      case 'status': {
        // Health frames carry a `V`; state reports (the bulk) are skipped unparsed.
        if (t.id === this.selected || !payload.includes(0x56)) return;
        this.health.length = 0;
        this.reader.reset();
        this.reader.feed(payload);
        if (this.health.length > 0)
          this.dispatch({ kind: 'health', id: t.id, servos: [...this.health] });
        return;
      }
      case 'online':
        this.dispatch({ kind: 'online', id: t.id, text: decoder.decode(payload) });
        return;
      case 'profile': {
        if (payload.length === 0) return; // a cleared retained message
        const r = parseAnnouncement(decoder.decode(payload));
        if (!r.ok) {
          this.counters.badProfiles++;
          this.lastError = `arm/${t.id}/profile: ${r.error}`;
          return;
        }
        this.profiles.set(t.id, r.profile);
        this.dispatch({ kind: 'profile', id: t.id, name: r.profile.name, title: r.profile.title });
        for (const fn of this.profileListeners) fn(t.id, r.profile);
        return;
      }
      case 'feedback': {
        if (t.id !== this.selected) return;
        const f = parseFeedback(decoder.decode(payload));
        if (!f) {
          this.counters.badFeedback++;
          return;
        }
        for (const fn of this.feedbackListeners) fn(f);
        return;
      }
      // Not subscribed to: nothing of these comes.
      case 'control':
      case 'operator':
      case 'request':
      case 'sim':
      case 'torque':
        return;
      default:
        return unhandled(p.kind);
    }
  }
}
