/**
 * The fleet's MQTT edge: one mqtt.js client (injected, like ArmLink's) beside the arm link. It
 * follows every arm on the broker at a low rate, whatever the fleet's size: the retained
 * `arm/+/online`, `arm/+/profile` and `arm/+/summary` (docs/protocol.md § Fleets: state, worst
 * health, holder, pose at 2 Hz, at once on an alarm) and the thermal model's early warnings on
 * `arm/+/alert`; never another arm's full-rate status (the shown arm's comes through the store).
 * Also the selected arm's motion feedback; it publishes motion requests on `arm/{id}/request`.
 * Bad input is counted by kind. Plain state, no React: panels sample `state` and `version`.
 */
import {
  allArmsTopic,
  armTopics,
  CLEAN_SESSION_SUBSCRIBE_QOS as QOS,
  isValidArmId,
  parseSummary,
  parseTopic,
  unhandled,
} from '@armtwin/protocol';
import { parseAnnouncement, type Profile } from '@armtwin/robot';
import type { MotionRequest } from '@armtwin/motion';
import { parseThermalAlert } from '@armtwin/thermal';
import { connectOptions, type ConnectOptions } from '../link/connectOptions.ts';
import type { MqttLike } from '../link/MqttLike.ts';
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

export interface FleetCounters {
  messages: number;
  /** Announcements that failed `parseProfile` (the arm keeps its previous profile). */
  badProfiles: number;
  /** Feedback that was not a feedback object. */
  badFeedback: number;
  /** Summaries `parseSummary` refused (the arm keeps its previous row). */
  badSummaries: number;
  /** Early warnings that were not one. */
  badAlerts: number;
  requests: number;
}

/** The first refusal of each kind of fleet input, as text (Status panel). */
export type FleetFirstErrors = Partial<Record<'profile' | 'summary' | 'alert', string>>;

const decoder = new TextDecoder();

export class FleetLink {
  state: FleetState = EMPTY_FLEET;
  /** Bumped when an arm appears or its row changes (online, profile, health level). */
  version = 0;
  /** Parsed profile per arm id, from the retained announcements. */
  readonly profiles = new Map<string, Profile>();
  readonly counters: FleetCounters = {
    messages: 0,
    badProfiles: 0,
    badFeedback: 0,
    badSummaries: 0,
    badAlerts: 0,
    requests: 0,
  };
  /** First refusal per kind of input (Status panel). */
  readonly firstError: FleetFirstErrors = {};
  connected = false;
  lastError = '';
  private client: FleetMqtt | null = null;
  private selected: string;
  private readonly profileListeners = new Set<(armId: string, profile: Profile) => void>();
  private readonly feedbackListeners = new Set<(f: Feedback) => void>();

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
      const topics = [
        allArmsTopic('online'),
        allArmsTopic('profile'),
        allArmsTopic('summary'),
        allArmsTopic('alert'),
        armTopics(this.selected).feedback,
      ];
      // QoS 0: the page's session is clean (docs/protocol.md § Several brokers).
      client.subscribe(topics, { qos: QOS }, (err) => {
        if (err) this.lastError = `fleet subscribe failed: ${err.message}`;
      });
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

  /** Follows another arm's motion feedback. */
  select(armId: string): void {
    if (!isValidArmId(armId) || armId === this.selected) return;
    const old = this.selected;
    this.selected = armId;
    const c = this.client;
    if (!c) return;
    c.unsubscribe([armTopics(old).feedback]);
    c.subscribe([armTopics(armId).feedback], { qos: QOS });
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

  private dispatch(ev: FleetEvent): void {
    const before = this.state.get(ev.id);
    this.state = reduceFleet(this.state, ev);
    if (!sameSummary(before, this.state.get(ev.id))) this.version++;
  }

  private refuse(kind: keyof FleetFirstErrors, armId: string, error: string): void {
    this.lastError = `arm/${armId}/${kind}: ${error}`;
    this.firstError[kind] ??= this.lastError;
  }

  private onMessage(topic: string, payload: Uint8Array): void {
    this.counters.messages++;
    const p = parseTopic(topic);
    if (!p) return;
    const t = { id: p.armId };
    switch (p.kind) {
      case 'summary': {
        if (payload.length === 0)
          return this.dispatch({ kind: 'summary', id: t.id, summary: null });
        const r = parseSummary(payload);
        if (!r.ok) {
          this.counters.badSummaries++;
          return this.refuse('summary', t.id, r.error);
        }
        return this.dispatch({ kind: 'summary', id: t.id, summary: r.summary });
      }
      case 'alert': {
        const alert = parseThermalAlert(payload);
        if (!alert) {
          this.counters.badAlerts++;
          return this.refuse('alert', t.id, 'not an early warning');
        }
        return this.dispatch({ kind: 'alert', id: t.id, alert });
      }
      case 'online':
        this.dispatch({ kind: 'online', id: t.id, text: decoder.decode(payload) });
        return;
      case 'profile': {
        if (payload.length === 0) return; // a cleared retained message
        const r = parseAnnouncement(decoder.decode(payload));
        if (!r.ok) {
          this.counters.badProfiles++;
          return this.refuse('profile', t.id, r.error);
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
      case 'status':
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
