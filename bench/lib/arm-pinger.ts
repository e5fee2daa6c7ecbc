/**
 * Which arms hear their control topic (bench sections on a cluster): a client on a broker list
 * sends `$PNG:<n>!` to each arm's `arm/{id}/control` and watches `arm/+/status` for the echo,
 * asking again every `retryMs` until every arm has answered. It also counts the status messages
 * of each arm it sees (QoS 0: what a live subscriber gets), and the reports in them (`$TIM`
 * stamps: a message may join several, packages/link/src/joined-stream.ts).
 */
import { connectBrokers, parseBrokerList, type BrokerClient } from '@armtwin/link';
import { linkOptions } from '@armtwin/protocol';
import { sleep } from './proc.ts';

export interface ArmPinger {
  client: BrokerClient;
  /** Status messages seen per arm id. */
  seen: Map<string, number>;
  /** `$TIM`-stamped reports seen per arm id. */
  reports: Map<string, number>;
  /**
   * Pings every arm of `ids` until each has echoed a ping sent in this call, or `timeoutMs`
   * passes; resolves with the arms that never answered.
   */
  untilAllAnswer(ids: readonly string[], timeoutMs: number, retryMs?: number): Promise<string[]>;
  end(): Promise<void>;
}

export function armPinger(brokers: string, clientId: string): ArmPinger {
  const client = connectBrokers(parseBrokerList(brokers), { clientId, ...linkOptions() });
  client.on('error', () => {});
  const seen = new Map<string, number>();
  const reports = new Map<string, number>();
  const echoed = new Set<string>();
  let round = 0;
  client.on('message', (topic, payload) => {
    const arm = topic.split('/')[1]!;
    seen.set(arm, (seen.get(arm) ?? 0) + 1);
    const text = payload.toString();
    reports.set(arm, (reports.get(arm) ?? 0) + text.split('$TIM:').length - 1);
    const ping = /\$PNG:(\d+)!/.exec(text);
    if (ping) echoed.add(`${arm}:${ping[1]}`);
  });
  client.on('connect', () => void client.subscribe('arm/+/status', { qos: 0 }));
  return {
    client,
    seen,
    reports,
    async untilAllAnswer(ids, timeoutMs, retryMs = 2000) {
      const tag = ++round;
      const deadline = Date.now() + timeoutMs;
      let waiting = [...ids];
      while (waiting.length > 0 && Date.now() < deadline) {
        if (client.connected)
          for (const id of waiting) client.publish(`arm/${id}/control`, `$PNG:${tag}!`, { qos: 0 });
        const until = Math.min(deadline, Date.now() + retryMs);
        while (Date.now() < until && waiting.some((id) => !echoed.has(`${id}:${tag}`)))
          await sleep(100);
        waiting = waiting.filter((id) => !echoed.has(`${id}:${tag}`));
      }
      return waiting;
    },
    end: () => client.endAsync(true).then(() => {}),
  };
}
