/**
 * The arm link's side of an arm's model copy `{id}-model` (docs/protocol.md § Modes): in Model
 * mode the link reads the copy's status (into the copy's store, drawn beside the arm), online,
 * holder and audit (into the copy's control claim), and holds the copy's deadman as it holds the
 * arm's. A plain object ArmLink (./ArmLink.ts) owns; it publishes through the link's client.
 */
import { armTopics, auditTopic, CLEAN_SESSION_SUBSCRIBE_QOS, holderTopic } from '@armtwin/protocol';
import type { ArmStore } from '../store/ArmStore.ts';
import { modelArmId } from './modes.ts';
import type { ControlClaim } from './ControlClaim.ts';
import type { MqttLike } from './MqttLike.ts';

const decoder = new TextDecoder();

export class ModelCopySide {
  /** The copy's arm id; null for an arm that cannot have one (no Model mode then). */
  readonly id: string | null;
  /** Where the copy's status lands (the page's ModeSwitch store), once in Model mode. */
  store: ArmStore | null = null;

  constructor(
    armId: string,
    /** This page's claims on the copy (rebuilt with the link's identity). */
    public claim: ControlClaim,
    private readonly onError: (message: string) => void,
    private readonly now: () => number,
  ) {
    this.id = modelArmId(armId);
  }

  /** status, online, holder, audit of the copy ([] without one). */
  get topics(): string[] {
    const id = this.id;
    if (!id) return [];
    const t = armTopics(id);
    return [t.status, t.online, holderTopic(id), auditTopic(id)];
  }

  /** Into Model mode (or connected in it): read the copy, hold its deadman. */
  enter(client: MqttLike, deadman: boolean): void {
    client.subscribe(this.topics, { qos: CLEAN_SESSION_SUBSCRIBE_QOS }, (err) => {
      if (err) this.onError(`subscribe failed: ${err.message}`);
    });
    if (deadman) this.holdOperator(client, '1');
  }

  /** Out of Model mode: the copy's claim released, its deadman let go, its topics too. */
  leave(client: MqttLike, deadman: boolean): void {
    if (this.claim.holding) client.publish(this.claim.claimTopic, 'release', { qos: 1 });
    if (deadman) this.holdOperator(client, '0');
    client.unsubscribe?.(this.topics);
  }

  /** The copy's deadman (`arm/{id}-model/operator`), retained, as the arm's. */
  holdOperator(client: MqttLike, value: '0' | '1'): void {
    if (this.id) client.publish(armTopics(this.id).operator, value, { qos: 1, retain: true });
  }

  /** A message on one of the copy's topics; false for any other topic. */
  onMessage(topic: string, payload: Uint8Array): boolean {
    const [status, online, holder, audit] = this.topics;
    if (status === undefined) return false;
    if (topic === status) {
      if (this.store) {
        this.store.connection = 'connected'; // read on the link's connection
        this.store.ingest(payload, this.now());
      }
    } else if (topic === holder) this.claim.onHolder(payload);
    else if (topic === audit) this.claim.onAudit(payload);
    else if (topic === online) {
      if (this.store) this.store.armOnline = decoder.decode(payload).trim() === '1';
    } else return false;
    return true;
  }

  /** The link's connection dropped. */
  lost(): void {
    if (this.store) this.store.connection = 'offline';
  }
}
