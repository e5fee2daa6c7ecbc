/**
 * A fleet step's simulators (issue 34 item 3): arms 1…N spread over P processes of
 * ../agents/fleet.ts (./fleet-steps.ts says how), each hosting a range of arms. Takes rate
 * snapshots from all of them at once (SIGUSR2) and, on stop, what every arm published.
 */
import path from 'node:path';
import { startAgent } from './stack.ts';
import type { Child } from './proc.ts';
import { ratesByArm, splitArms, type ArmPublished } from './fleet-steps.ts';

/** The JSON lines a child prints on stdout, one at a time, each awaited with a bound. */
function lineReader(child: Child, what: string) {
  const lines: string[] = [];
  const waiting: (() => void)[] = [];
  let buf = '';
  child.proc.stdout?.on('data', (d: Buffer) => {
    buf += d.toString();
    for (let nl = buf.indexOf('\n'); nl >= 0; nl = buf.indexOf('\n')) {
      lines.push(buf.slice(0, nl));
      buf = buf.slice(nl + 1);
      waiting.splice(0).forEach((w) => w());
    }
  });
  let gone = false;
  void child.exited.then(() => {
    gone = true;
    waiting.splice(0).forEach((w) => w());
  });
  return async function next<T>(timeoutMs: number): Promise<T> {
    const deadline = Date.now() + timeoutMs;
    while (!lines.length) {
      if (gone) throw new Error(`${what} exited without its next line`);
      const left = deadline - Date.now();
      if (left <= 0) throw new Error(`${what} printed nothing in ${timeoutMs} ms`);
      await new Promise<void>((r) => {
        const t = setTimeout(r, left);
        waiting.push(() => {
          clearTimeout(t);
          r();
        });
      });
    }
    return JSON.parse(lines.shift()!) as T;
  };
}

interface Snapshot {
  atMs: number;
  samples: Record<string, number>;
}

export interface FleetSims {
  pids: number[];
  /** Rate snapshot of every process now; `rates` between two gives each arm's samples/s. */
  snapshot(): Promise<Snapshot[]>;
  /** Stops every arm, then every process; what each arm published over its life. */
  stop(): Promise<Record<string, ArmPublished>>;
}

export async function startFleetSims(o: {
  url: string;
  arms: number;
  processes: number;
  rateHz: number;
  prefix: string;
  logDir: string;
}): Promise<FleetSims> {
  const ranges = splitArms(o.arms, o.processes);
  const agents = ranges.map(([first, last], k) => {
    const child = startAgent(
      'fleet',
      [o.url, String(first), String(last), String(o.rateHz), o.prefix],
      path.join(o.logDir, `fleet-sims-${o.prefix}${k + 1}.log`),
    );
    return { child, next: lineReader(child, `fleet agent ${o.prefix}${first}…${last}`) };
  });
  const stopAll = () => Promise.all(agents.map((a) => a.child.stop(10_000)));
  try {
    await Promise.all(
      agents.map((a, k) => a.next(60_000 + (ranges[k]![1] - ranges[k]![0] + 1) * 500)),
    );
  } catch (err) {
    await stopAll();
    throw err;
  }
  return {
    pids: agents.map((a) => a.child.pid),
    async snapshot() {
      for (const a of agents) a.child.proc.kill('SIGUSR2');
      return Promise.all(agents.map((a) => a.next<Snapshot>(10_000)));
    },
    async stop() {
      const finals = agents.map((a) => a.next<{ published: Record<string, ArmPublished> }>(30_000));
      for (const a of agents) a.child.proc.kill('SIGTERM');
      const out = Object.assign({}, ...(await Promise.all(finals)).map((f) => f.published)) as Record<
        string,
        ArmPublished
      >;
      await stopAll();
      return out;
    },
  };
}

/** Each arm's state samples a second between two snapshots of the same processes. */
export function windowRates(a: Snapshot[], b: Snapshot[]): Record<string, number> {
  return Object.assign({}, ...a.map((s, k) => ratesByArm(s, b[k]!))) as Record<string, number>;
}
