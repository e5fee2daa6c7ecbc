/**
 * What the arm link reads: the topics it subscribes at every connect and where each message
 * goes. Status into the store (no React), everyone's commands for the predictive twin, the
 * holder and audit into the page's claim on the arm, the model copy's topics to its side, the
 * arm's online flag, and the rest to the link's taps. A plain object ArmLink (./ArmLink.ts) owns.
 */
import {
  auditTopic,
  CLEAN_SESSION_SUBSCRIBE_QOS as QOS,
  holderTopic,
  topic,
  type ArmTopics,
} from '@armtwin/protocol';
import type { ArmStore } from '../store/ArmStore.ts';
import type { ControlClaim } from './ControlClaim.ts';
import type { ModelCopySide } from './ModelCopySide.ts';
import type { MqttLike } from './MqttLike.ts';
import type { OwnEchoes } from './OwnEchoes.ts';

/**
 * Another reader of this link's client (the cameras of the arm, src/core/cameras/CameraHub.ts): its
 * filter is subscribed at every connect, with the link's log-in; matching messages go to it.
 */
export interface LinkTap {
  readonly filter: string;
  matches(topic: string): boolean;
  onMessage(topic: string, payload: Uint8Array): void;
}

const decoder = new TextDecoder();

export class LinkInbox {
  private readonly taps: LinkTap[] = [];
  private readonly holderTopic: string;
  private readonly auditTopic: string;
  private readonly summaryTopic: string;

  constructor(
    armId: string,
    private readonly topics: ArmTopics,
    private readonly store: ArmStore,
    /** This page's claim on the arm (replaced when the link starts as a user). */
    private readonly armClaim: () => ControlClaim,
    private readonly copy: ModelCopySide,
    /** A failed subscription, said on the page. */
    readonly onSubscribed: (err: Error | null) => void,
    private readonly now: () => number,
    /** What this page sent and its twin has noted: not noted again when it comes back. */
    private readonly own: OwnEchoes,
  ) {
    this.holderTopic = holderTopic(armId);
    this.auditTopic = auditTopic(armId);
    this.summaryTopic = topic(armId, 'summary');
  }

  /**
   * At every connect: the arm's topics and the taps'; the copy's in Model mode (`inModel`,
   * holding its deadman with `deadman`); everyone's commands last. All at QoS 0: the page's
   * session is clean (`CLEAN_SESSION_SUBSCRIBE_QOS`, docs/protocol.md § Several brokers).
   */
  subscribe(client: MqttLike, inModel: boolean, deadman: boolean): void {
    // The summary names the holder until the holder record comes (ControlClaim.onSummary).
    client.subscribe(
      [
        this.topics.status,
        this.topics.online,
        this.summaryTopic,
        this.holderTopic,
        this.auditTopic,
      ],
      { qos: QOS },
      this.onSubscribed,
    );
    this.subscribeTaps(client);
    if (inModel) this.copy.enter(client, deadman);
    // Everyone's commands, for the predictive twin; a broker may refuse a role this (ACL).
    client.subscribe([`${this.topics.control}/#`], { qos: QOS }, () => {});
  }

  /** Adds a reader; `client` (when connected) subscribes its filter now, else at connect. */
  tap(t: LinkTap, client: MqttLike | null): void {
    this.taps.push(t);
    if (client) this.subscribeTaps(client, [t]);
  }

  private subscribeTaps(client: MqttLike, taps: readonly LinkTap[] = this.taps): void {
    if (taps.length === 0) return;
    client.subscribe(
      taps.map((t) => t.filter),
      { qos: QOS },
      this.onSubscribed,
    );
  }

  onMessage(topic: string, payload: Uint8Array): void {
    if (topic === this.topics.status) {
      this.store.ingest(payload, this.now());
    } else if (topic === this.topics.control || topic.startsWith(`${this.topics.control}/`)) {
      const now = this.now();
      if (!this.own.take(topic, payload, now)) this.store.noteControl(payload, now);
    } else if (topic === this.holderTopic) {
      this.armClaim().onHolder(payload);
    } else if (topic === this.auditTopic) {
      this.armClaim().onAudit(payload);
    } else if (topic === this.summaryTopic) {
      this.armClaim().onSummary(payload);
    } else if (this.copy.onMessage(topic, payload)) {
      // the model copy's (Model mode)
    } else if (topic === this.topics.online) {
      const text = decoder.decode(payload).trim();
      this.store.armOnline = text === '1' ? true : text === '0' ? false : null;
      this.store.armOnlineText = this.store.armOnline === null ? text.slice(0, 80) : '';
    } else {
      for (const t of this.taps) if (t.matches(topic)) t.onMessage(topic, payload);
    }
  }
}
