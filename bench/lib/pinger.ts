/**
 * The round-trip pinger of bench/rtt.ts: one mqtt.js client that publishes `$PNG:n!` on a
 * path's control topic and times each echo on its status topic with `process.hrtime.bigint()`;
 * loss, duplicates and reordering are counted by sequence number.
 */
import type { MqttClient } from 'mqtt';
import { sleep } from './proc.ts';
const PNG = /\$PNG:(\d+)!/g;

export interface Path {
  name: 'sim' | 'echo';
  control: string;
  status: string;
}

export interface PingRun {
  sent: number;
  received: number;
  lost: number;
  duplicates: number;
  outOfOrder: number;
  durationS: number;
  rttMs: number[];
}

/** One pinger client; `run` sends `count` pings and collects their echoes. */
export class Pinger {
  private seq = 1;
  private sentAt = new Map<number, bigint>();
  private rtts: number[] = [];
  private seen = new Set<number>();
  private dup = 0;
  private ooo = 0;
  private maxSeen = 0;
  private lo = 0;
  private waiter: ((seq: number) => void) | null = null;

  constructor(private readonly client: MqttClient) {
    client.on('message', (_topic, payload) => {
      const at = process.hrtime.bigint();
      const text = payload.toString('latin1');
      if (!text.includes('$PNG:')) return; // state and health payloads of the sim
      for (const m of text.matchAll(PNG)) this.echo(Number(m[1]), at);
    });
  }

  private echo(seq: number, at: bigint): void {
    if (seq < this.lo) return; // a straggler of an earlier run
    const t = this.sentAt.get(seq);
    if (t === undefined) return;
    if (this.seen.has(seq)) {
      this.dup++;
      return;
    }
    this.seen.add(seq);
    if (seq < this.maxSeen) this.ooo++;
    this.maxSeen = Math.max(this.maxSeen, seq);
    this.rtts.push(Number(at - t) / 1e6);
    this.waiter?.(seq);
  }

  private reset(): void {
    this.lo = this.seq;
    this.sentAt.clear();
    this.seen.clear();
    this.rtts = [];
    this.dup = this.ooo = 0;
    this.maxSeen = 0;
  }

  private send(topic: string): number {
    const s = this.seq++;
    this.sentAt.set(s, process.hrtime.bigint());
    this.client.publish(topic, `$PNG:${s}!`, { qos: 1 });
    return s;
  }

  private result(t0: bigint): PingRun {
    const sent = this.sentAt.size;
    return {
      sent,
      received: this.seen.size,
      lost: sent - this.seen.size,
      duplicates: this.dup,
      outOfOrder: this.ooo,
      durationS: Number(process.hrtime.bigint() - t0) / 1e9,
      rttMs: this.rtts,
    };
  }

  /** One at a time: the next ping leaves when the echo is back (or after timeoutMs). */
  async sequential(p: Path, count: number, timeoutMs = 1000): Promise<PingRun> {
    this.reset();
    const t0 = process.hrtime.bigint();
    for (let i = 0; i < count; i++) {
      await new Promise<void>((resolve) => {
        const s = this.send(p.control);
        const timer = setTimeout(done, timeoutMs);
        this.waiter = (seq) => seq === s && done();
        function done() {
          clearTimeout(timer);
          resolve();
        }
      });
    }
    this.waiter = null;
    return this.result(t0);
  }

  /** `count` pings one at a time on each path, alternating a, b, a, b … (side by side). */
  async alternating(a: Path, b: Path, count: number): Promise<[PingRun, PingRun]> {
    const ra: PingRun[] = [];
    const rb: PingRun[] = [];
    for (let i = 0; i < count; i++) {
      ra.push(await this.sequential(a, 1));
      rb.push(await this.sequential(b, 1));
    }
    return [merge(ra), merge(rb)];
  }

  /** Open loop at `hz`: every ping due by absolute time leaves at each wake-up. */
  async paced(p: Path, count: number, hz: number, graceMs = 2000): Promise<PingRun> {
    this.reset();
    const t0 = process.hrtime.bigint();
    const start = performance.now();
    const deadline = start + (count / hz) * 1000 * 2 + 5000;
    let sent = 0;
    await new Promise<void>((resolve) => {
      const tick = () => {
        const now = performance.now();
        const due = Math.min(count, Math.floor(((now - start) * hz) / 1000) + 1);
        while (sent < due) {
          this.send(p.control);
          sent++;
        }
        if (sent >= count || now > deadline) return resolve();
        setTimeout(tick, Math.max(0, start + (sent * 1000) / hz - performance.now()));
      };
      tick();
    });
    const sendS = (performance.now() - start) / 1000;
    const until = Date.now() + graceMs;
    while (this.seen.size < this.sentAt.size && Date.now() < until) await sleep(20);
    return { ...this.result(t0), durationS: sendS };
  }
}

/** The runs of one path added up (blocks of one open-loop experiment). */
export function merge(runs: PingRun[]): PingRun {
  return runs.reduce(
    (a, r) => ({
      sent: a.sent + r.sent,
      received: a.received + r.received,
      lost: a.lost + r.lost,
      duplicates: a.duplicates + r.duplicates,
      outOfOrder: a.outOfOrder + r.outOfOrder,
      durationS: a.durationS + r.durationS,
      rttMs: a.rttMs.concat(r.rttMs),
    }),
    {
      sent: 0,
      received: 0,
      lost: 0,
      duplicates: 0,
      outOfOrder: 0,
      durationS: 0,
      rttMs: [] as number[],
    },
  );
}
