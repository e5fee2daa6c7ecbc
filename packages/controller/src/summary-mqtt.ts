/**
 * The arm's summary on MQTT (docs/protocol.md § Fleets), for any driver
 * (`@armtwin/controller/mqtt`): every status payload the driver publishes goes through `note`;
 * from `start` on, the summary (./summary.ts) is published retained on `arm/{id}/summary`, QoS 0,
 * every `SUMMARY_PERIOD_MS` while the client is connected, and at once when a payload raised an
 * alarm (no sooner than `SUMMARY_MIN_GAP_MS` after the last). `stop` clears the retained one.
 * The client and the clock are the driver's.
 */
import type { MqttClient } from 'mqtt';
import {
  encodeSummary,
  SUMMARY_MIN_GAP_MS,
  SUMMARY_PERIOD_MS,
  topic,
  type Clock,
  type HolderRecord,
} from '@armtwin/protocol';
import type { ControllerCore } from './core.ts';
import { SummaryTracker } from './summary.ts';

export interface ArmSummaryOut {
  readonly tracker: SummaryTracker;
  /** Summaries handed to the client, and of those, sent early for an alarm. */
  readonly counters: { published: number; alarms: number };
  /** A status payload the arm publishes (each one; cheap when it holds no health or `$ERR`). */
  note(payload: string | Uint8Array): void;
  /** Starts publishing, from this core and holder (read at each summary). */
  start(core: () => ControllerCore, holder: () => HolderRecord): void;
  /** Stops publishing and clears the retained summary (while connected). */
  stop(): Promise<void>;
}

type Client = Pick<MqttClient, 'connected' | 'publish' | 'publishAsync'>;

export function armSummary(
  client: Client,
  armId: string,
  clock: Clock,
  periodMs = SUMMARY_PERIOD_MS,
): ArmSummaryOut {
  const summaryTopic = topic(armId, 'summary');
  const tracker = new SummaryTracker();
  const counters = { published: 0, alarms: 0 };
  let source: { core: () => ControllerCore; holder: () => HolderRecord } | null = null;
  let timer: unknown;
  let due = Infinity;
  let last = -Infinity;

  const at = (when: number) => {
    if (timer !== undefined) clock.clearTimeout(timer);
    due = when;
    timer = clock.setTimeout(tick, Math.max(0, when - clock.now()));
  };
  const tick = () => {
    timer = undefined;
    if (!source) return;
    const now = clock.now();
    if (client.connected) {
      const s = tracker.summary(source.core(), source.holder().user, now);
      client.publish(summaryTopic, encodeSummary(s), { qos: 0, retain: true });
      counters.published++;
      last = now;
    }
    at(now + periodMs);
  };

  return {
    tracker,
    counters,
    note(payload) {
      if (!tracker.note(payload, clock.now()) || !source) return;
      const soonest = Math.max(clock.now(), last + SUMMARY_MIN_GAP_MS);
      if (soonest >= due) return; // one is coming as soon as allowed anyway
      counters.alarms++;
      at(soonest);
    },
    start(core, holder) {
      source = { core, holder };
      at(clock.now());
    },
    async stop() {
      source = null;
      if (timer !== undefined) clock.clearTimeout(timer);
      timer = undefined;
      due = Infinity;
      if (client.connected)
        await client.publishAsync(summaryTopic, '', { qos: 1, retain: true }).catch(() => {});
    },
  };
}
