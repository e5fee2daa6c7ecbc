/**
 * A fleet step's simulators (issue 34 item 3): arms 1…N spread over P processes of
 * ../agents/fleet.ts (./fleet-steps.ts says how), each hosting a range of arms. Takes rate
 * snapshots from all of them at once (SIGUSR2) and, on stop, what every arm published; measures
 * a window (rates, CPU, memory); reads back what InfluxDB holds per arm.
 */
import fs from 'node:fs';
import path from 'node:path';
import { startAgent } from './stack.ts';
import { cpuMeter, sleep, type Child } from './proc.ts';
import {
  rateSummary,
  ratesByArm,
  splitArms,
  type ArmPublished,
  type RateSummary,
} from './fleet-steps.ts';

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
  /** State samples and state payloads (messages) each arm published so far. */
  samples: Record<string, number>;
  payloads: Record<string, number>;
  /** Status messages of every kind (state, health, replies) all its arms published so far. */
  messages: number;
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
      try {
        return Object.assign({}, ...(await Promise.all(finals)).map((f) => f.published)) as Record<
          string,
          ArmPublished
        >;
      } finally {
        await stopAll();
      }
    },
  };
}

/** Each arm's state samples (or payloads) a second between two snapshots of the same processes. */
export function windowRates(
  a: Snapshot[],
  b: Snapshot[],
  what: 'samples' | 'payloads' = 'samples',
): Record<string, number> {
  const pick = (s: Snapshot) => ({ atMs: s.atMs, samples: s[what] });
  return Object.assign({}, ...a.map((s, k) => ratesByArm(pick(s), pick(b[k]!)))) as Record<
    string,
    number
  >;
}

/** Resident memory of a process, MiB (NaN once it is gone). */
function rssMiB(pid: number): number {
  try {
    const m = /VmRSS:\s+(\d+) kB/.exec(fs.readFileSync(`/proc/${pid}/status`, 'utf8'));
    return m ? Number(m[1]) / 1024 : NaN;
  } catch {
    return NaN;
  }
}

export interface Window {
  /** Each arm's state samples a second, and state payloads (messages) a second. */
  rates: RateSummary;
  payloads: RateSummary;
  /** Status messages the arms published in the window, and those the subscriber saw then. */
  publishedMessages: number;
  seen: number;
  /** Share of a core and resident MiB: each simulator process, then each of `others`. */
  cpu: number[];
  rss: number[];
}

/** A measuring window of `windowS` over the simulators and the `others` processes. */
export async function measureWindow(
  sims: FleetSims,
  others: number[],
  seen: () => number,
  windowS: number,
  heldHz: number,
): Promise<Window> {
  const pids = [...sims.pids, ...others];
  const meters = pids.map((p) => cpuMeter(p));
  for (const m of meters) m.start();
  const seen0 = seen();
  const a = await sims.snapshot();
  await sleep(windowS * 1000);
  const b = await sims.snapshot();
  const seenN = seen() - seen0;
  const cpu = meters.map((m) => m.stop().share);
  return {
    rates: rateSummary(windowRates(a, b), heldHz),
    payloads: rateSummary(windowRates(a, b, 'payloads')),
    publishedMessages: b.reduce((n, s, k) => n + s.messages - a[k]!.messages, 0),
    seen: seenN,
    cpu,
    rss: pids.map(rssMiB),
  };
}

/** Servo points (angles and temperatures) InfluxDB holds per arm for arms named `prefix…`. */
export async function storedByArm(
  url: string,
  db: string,
  prefix: string,
): Promise<Record<string, number>> {
  const q = `SELECT count("angle"), count("temp") FROM "servo" WHERE "arm" =~ /^${prefix}/ GROUP BY "arm"`;
  const res = await fetch(`${url}/query?db=${encodeURIComponent(db)}`, {
    method: 'POST',
    body: new URLSearchParams({ q }),
  }).catch(() => null);
  const out: Record<string, number> = {};
  if (!res?.ok) return out;
  const body = (await res.json()) as {
    results?: { series?: { tags?: { arm?: string }; values: unknown[][] }[] }[];
  };
  for (const s of body.results?.[0]?.series ?? []) {
    const v = s.values[0] ?? [];
    if (s.tags?.arm) out[s.tags.arm] = Number(v[1] ?? 0) + Number(v[2] ?? 0);
  }
  return out;
}
