/**
 * Whether each arm hears its control topic (a test on a cluster, after a node went down): a
 * client on a broker list sends `$PNG:<n>!` to `arm/{id}/control` (QoS 1) and watches
 * `arm/+/status` for the echo, asking again until it comes. It also keeps when each arm last
 * reported and whom each arm's live summary (not a retained one) names as holder, to say why
 * when an arm stays silent. (bench/lib/arm-pinger.ts is the bench's counting cousin.)
 */
import { connectBrokers, parseBrokerList, type BrokerClient } from '@armtwin/link';
import { linkOptions, parseSummary } from '@armtwin/protocol';
import { until } from './until.ts';

const sleep = (ms: number) => new Promise((r) => setTimeout(r, ms));

export interface ArmEchoes {
  client: BrokerClient;
  /** Whom each arm's latest live summary names as holder. */
  summaryHolder: Map<string, string | null>;
  /**
   * Pings `arm` with `$PNG:<seq>!` every 800 ms until it echoes, for at most `ms`; on a timeout
   * the error says when the arm last reported and what `log` says of it.
   */
  untilEchoed(
    arm: string,
    seq: number,
    ms: number,
    what: string,
    log: readonly string[],
  ): Promise<void>;
}

export function armEchoes(brokers: string, clientId: string): ArmEchoes {
  const client = connectBrokers(parseBrokerList(brokers), { clientId, ...linkOptions() });
  const echoed = new Set<string>();
  const lastReport = new Map<string, number>();
  const summaryHolder = new Map<string, string | null>();
  client.on('message', (t, p, packet) => {
    if (t.endsWith('/summary')) {
      const s = parseSummary(p);
      if (s.ok && !packet.retain) summaryHolder.set(t.split('/')[1]!, s.summary.holder);
      return;
    }
    lastReport.set(t, Date.now());
    const ping = /\$PNG:(\d+)!/.exec(p.toString());
    if (ping) echoed.add(`${t.split('/')[1]}:${ping[1]}`);
  });
  client.on('connect', () => void client.subscribe(['arm/+/status', 'arm/+/summary'], { qos: 0 }));
  return {
    client,
    summaryHolder,
    untilEchoed: (arm, seq, ms, what, log) =>
      until(
        async () => {
          if (client.connected)
            await client.publishAsync(`arm/${arm}/control`, `$PNG:${seq}!`, { qos: 1 });
          await sleep(800);
          return echoed.has(`${arm}:${seq}`);
        },
        ms,
        what,
        200,
      ).then(
        () => {},
        (err: Error) => {
          const seen = lastReport.get(`arm/${arm}/status`);
          const said = log.filter((l) => l.includes(`"${arm}"`) || l.includes('subscribe'));
          throw new Error(
            `${err.message}; its last report ${seen ? `${Date.now() - seen} ms ago` : 'never seen'}; ` +
              `its log:\n${said.join('')}`,
          );
        },
      ),
  };
}
