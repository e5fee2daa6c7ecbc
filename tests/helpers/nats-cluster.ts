/**
 * A throwaway 3-node NATS cluster on 127.0.0.1 (docs/cluster.md): every node runs JetStream
 * (its store in its own temp dir), MQTT (sessions, retained messages and QoS 1 messages kept in
 * JetStream with 3 replicas) and MQTT over WebSockets (`ws://…/mqtt`, as the page connects),
 * and routes to the other two. The binary is `.tools/bin/nats-server` (scripts/build-nats.sh).
 * Each node can be killed (SIGKILL: a crash) and started again in its own dir, where it rejoins.
 */
import fs from 'node:fs';
import path from 'node:path';
import { REPO_ROOT } from './files.ts';
import { freePorts, LOOPBACK } from './ports.ts';
import { ServiceProcess } from './process.ts';
import { makeTempDir } from './files.ts';
import { connect } from '@nats-io/transport-node';

export const NATS_SERVER = path.join(REPO_ROOT, '.tools', 'bin', 'nats-server');

export interface NatsNode {
  name: string;
  /** `mqtt://127.0.0.1:<port>` */
  mqttUrl: string;
  /** `ws://127.0.0.1:<port>/mqtt` (MQTT over WebSockets, as the page speaks it) */
  wsUrl: string;
  /** `nats://127.0.0.1:<port>` (the engine's own protocol: the middleware's NATS intake) */
  natsUrl: string;
  /** The monitoring endpoint (`/healthz`, `/routez`, `/jsz`). */
  monitorUrl: string;
  readonly running: boolean;
  readonly process: ServiceProcess;
}

export interface NatsCluster {
  nodes: NatsNode[];
  /** Every node's MQTT URL, from node `first` round: a part's broker list. */
  mqttUrls(first?: number): string;
  wsUrls(first?: number): string;
  natsUrls(first?: number): string;
  /** The other nodes node `i` has routes to (its `/routez`), 0 while it is down. */
  routes(i: number): Promise<number>;
  /**
   * The node leading a JetStream stream (`$MQTT_msgs`: MQTT's QoS 1 messages) and the nodes whose
   * copy of it is current (the leader first), as the leader's `/jsz` tells; null while nobody leads it.
   */
  stream(name: string): Promise<{ leader: string; current: string[] } | null>;
  /**
   * Has node `i` give up leading a stream (JetStream's leader step-down, as `nats stream cluster
   * step-down` does) until another node leads it; nothing when it does not lead it.
   */
  leadAwayFrom(name: string, i: number): Promise<void>;
  /** Kills every node; with `keepLogs`, says where the logs were kept. */
  dispose(opts?: { keepLogs?: boolean }): Promise<string | undefined>;
}

interface Jsz {
  account_details?: {
    stream_detail?: {
      name: string;
      cluster?: { leader?: string; replicas?: { name: string; current: boolean }[] };
    }[];
  }[];
}

const PORTS_PER_NODE = 5; // client, cluster, MQTT, WebSockets, monitoring

function nodeConf(i: number, dir: string, ports: number[][]): string {
  const [client, cluster, mqtt, ws, http] = ports[i]!;
  const routes = ports
    .filter((_, j) => j !== i)
    .map((p) => `"nats-route://${LOOPBACK}:${p[1]}"`)
    .join(', ');
  return [
    '# written by tests/helpers/nats-cluster.ts',
    `server_name: n${i + 1}`,
    `listen: "${LOOPBACK}:${client}"`,
    `http: "${LOOPBACK}:${http}"`,
    `jetstream { store_dir: "${path.join(dir, 'js')}" }`,
    `cluster { name: armtwin, listen: "${LOOPBACK}:${cluster}", routes: [${routes}] }`,
    // MQTT's streams (sessions, retained, QoS 1 messages) and their consumers on all 3 nodes.
    `mqtt { listen: "${LOOPBACK}:${mqtt}", stream_replicas: 3 }`,
    `websocket { listen: "${LOOPBACK}:${ws}", no_tls: true }`,
    '',
  ].join('\n');
}

/** Starts 3 nodes together and resolves once every one answers `/healthz` (JetStream current). */
export async function startNatsCluster(): Promise<NatsCluster> {
  if (!fs.existsSync(NATS_SERVER))
    throw new Error(`${NATS_SERVER} not found; run scripts/install-deps.sh`);
  const flat = await freePorts(3 * PORTS_PER_NODE);
  const ports = [0, 1, 2].map((i) => flat.slice(i * PORTS_PER_NODE, (i + 1) * PORTS_PER_NODE));
  const nodes = ports.map((p, i): NatsNode => {
    const dir = makeTempDir(`nats-n${i + 1}`);
    const confFile = path.join(dir, 'nats.conf');
    fs.writeFileSync(confFile, nodeConf(i, dir, ports));
    const monitorUrl = `http://${LOOPBACK}:${p[4]}`;
    const proc = new ServiceProcess({
      name: 'nats-server',
      command: NATS_SERVER,
      args: ['-c', confFile],
      dir,
      host: LOOPBACK,
      ports: [p[0]!, p[2]!, p[3]!],
      startTimeoutMs: 60_000,
      ready: async () => (await fetch(`${monitorUrl}/healthz`)).ok,
    });
    return {
      name: `n${i + 1}`,
      mqttUrl: `mqtt://${LOOPBACK}:${p[2]}`,
      wsUrl: `ws://${LOOPBACK}:${p[3]}/mqtt`,
      natsUrl: `nats://${LOOPBACK}:${p[0]}`,
      monitorUrl,
      get running() {
        return proc.running;
      },
      process: proc,
    };
  });
  try {
    // Together: a node's JetStream is ready only once the meta group has its quorum.
    await Promise.all(nodes.map((n) => n.process.start()));
  } catch (err) {
    await Promise.all(nodes.map((n) => n.process.dispose({ keepLogs: true })));
    throw err;
  }
  const list =
    (key: 'mqttUrl' | 'wsUrl' | 'natsUrl') =>
    (first = 0) =>
      nodes.map((_, j) => nodes[(first + j) % nodes.length]![key]).join(',');
  const stream = async (name: string) => {
    for (const n of nodes.filter((x) => x.running)) {
      const r = await fetch(`${n.monitorUrl}/jsz?accounts=true&streams=true`).catch(() => null);
      if (!r?.ok) continue;
      const jsz = (await r.json()) as Jsz;
      const s = jsz.account_details
        ?.flatMap((a) => a.stream_detail ?? [])
        .find((d) => d.name === name);
      // The leader's own view lists its followers and whether each is current.
      if (s?.cluster?.leader !== n.name) continue;
      const current = (s.cluster.replicas ?? []).filter((x) => x.current).map((x) => x.name);
      return { leader: s.cluster.leader, current: [s.cluster.leader, ...current] };
    }
    return null;
  };
  return {
    nodes,
    mqttUrls: list('mqttUrl'),
    wsUrls: list('wsUrl'),
    natsUrls: list('natsUrl'),
    async routes(i) {
      const n = nodes[i]!;
      if (!n.running) return 0;
      const r = await fetch(`${n.monitorUrl}/routez`).catch(() => null);
      if (!r?.ok) return 0;
      // Several route connections per peer (a pool): count the peers.
      const { routes } = (await r.json()) as { routes?: { remote_id: string }[] };
      return new Set((routes ?? []).map((x) => x.remote_id)).size;
    },
    stream,
    async leadAwayFrom(name, i) {
      const nc = await connect({ servers: nodes.filter((n) => n.running).map((n) => n.natsUrl) });
      try {
        for (let k = 0; k < 20; k++) {
          const s = await stream(name);
          if (s && s.leader !== nodes[i]!.name) return;
          if (s) await nc.request(`$JS.API.STREAM.LEADER.STEPDOWN.${name}`, '').catch(() => {});
          await new Promise((r) => setTimeout(r, 500));
        }
        throw new Error(`${nodes[i]!.name} still leads ${name}`);
      } finally {
        await nc.close();
      }
    },
    async dispose(opts = {}) {
      const kept = await Promise.all(nodes.map((n) => n.process.dispose(opts)));
      return kept.filter((k): k is string => !!k).join(', ') || undefined;
    },
  };
}
