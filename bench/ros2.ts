/**
 * ROS 2 (issue 31, item 3): seed 004's ping/pong on ROS 2 itself, and what armtwin's rclpy bridge
 * adds. All on real rclpy + FastDDS from the ROS 2 venv (scripts/install-ros2.sh), one private
 * ROS domain, an echo node (python/armtwin_ros2/pingpong.py) republishing every ping as a pong.
 *
 * - rclpy ⇄ rclpy at 1 kHz, 60,000 messages (quick: 5,000): loss by sequence number, round trip.
 * - At 100, 250 and 1000 Hz: the same echo pinged through the bridge (this process → JSON line →
 *   `bridge.py` → DDS → echo → DDS → `bridge.py` → JSON line → this process) beside rclpy direct
 *   at the same rate; the difference of the round trips is the bridge's latency both ways. CPU
 *   per 1,000 messages: the pinging side (direct: the ping process; bridged: this process and the
 *   bridge process), the echo's excluded (it is the same in both).
 * armtwin's MQTT round trip at 1 kHz is the rtt section's (same run). Before anything is timed,
 * the bridge pings until a pong comes back (discovery done both ways).
 */
import readline from 'node:readline';
import { Ros2Bridge, ros2Env, ros2Python } from '@armtwin/ros2';
import { cpuSeconds, spawnChild, type Child } from './lib/proc.ts';
import { round, summarize } from './lib/stats.ts';
import { fmt, type BenchContext, type Row, type Section, type SectionOutput } from './lib/types.ts';

const PING = '/armtwin_bench/ping';
const PONG = '/armtwin_bench/pong';
const RATES = [100, 250, 1000] as const;

interface PingResult {
  sent: number;
  received: number;
  lost: number;
  rate: number;
  p50_us: number | null;
  p99_us: number | null;
  max_us: number | null;
  cpu_s: number;
}

/** A pingpong.py process; resolves with it once it says ready, and with its result lines. */
async function pingpong(args: string[]): Promise<{ child: Child; lines: AsyncIterator<string> }> {
  const child = spawnChild(ros2Python(), ['-m', 'armtwin_ros2.pingpong', ...args], {
    env: ros2Env(),
    stdout: 'pipe',
  });
  const lines = readline.createInterface({ input: child.proc.stdout! })[Symbol.asyncIterator]();
  const first = await lines.next();
  if (first.done || !first.value.includes('ready'))
    throw new Error(`pingpong ${args[0]} did not start`);
  return { child, lines };
}

async function direct(domain: number, rate: number, count: number): Promise<PingResult> {
  const { child, lines } = await pingpong([
    'ping',
    '--domain',
    String(domain),
    '--rate',
    String(rate),
    '--count',
    String(count),
  ]);
  const line = await lines.next();
  await child.stop();
  if (line.done) throw new Error('pingpong ping ended without a result');
  return JSON.parse(line.value) as PingResult;
}

async function bridged(bridge: Ros2Bridge, rate: number, count: number) {
  const sentAt = new Map<number, bigint>();
  const rttUs: number[] = [];
  const seen = new Set<number>();
  const onPong = (m: { data: string }) => {
    const seq = Number(m.data);
    const t0 = sentAt.get(seq);
    if (t0 === undefined || seen.has(seq)) return;
    seen.add(seq);
    rttUs.push(Number(process.hrtime.bigint() - t0) / 1000);
  };
  handlers.current = onPong;
  const c0 = cpuSeconds(bridge.pid);
  const u0 = process.cpuUsage();
  const periodNs = BigInt(Math.round(1e9 / rate));
  const start = process.hrtime.bigint();
  for (let seq = 0; seq < count;) {
    const due = Number((process.hrtime.bigint() - start) / periodNs) + 1;
    for (; seq < Math.min(due, count); seq++) {
      sentAt.set(seq, process.hrtime.bigint());
      bridge.publish(PING, 'string', { data: String(seq) });
    }
    await new Promise((r) => setTimeout(r, 1));
  }
  const end = Date.now() + 2000;
  while (seen.size < count && Date.now() < end) await new Promise((r) => setTimeout(r, 10));
  const u = process.cpuUsage(u0);
  const cpuS = cpuSeconds(bridge.pid) - c0 + (u.user + u.system) / 1e6;
  const s = summarize(rttUs);
  return {
    sent: count,
    received: seen.size,
    lost: count - seen.size,
    p50_us: s.p50,
    p99_us: s.p99,
    max_us: s.max,
    cpu_s: cpuS,
  };
}
/** Pings (-1) until one comes back: both directions matched before anything is timed. */
async function warmUp(bridge: Ros2Bridge): Promise<void> {
  let back = false;
  handlers.current = (m) => (back ||= m.data === '-1');
  const end = Date.now() + 20_000;
  while (!back && Date.now() < end) {
    bridge.publish(PING, 'string', { data: '-1' });
    await new Promise((r) => setTimeout(r, 50));
  }
  if (!back) throw new Error('no pong through the bridge in 20 s');
}

/** The bridge's one pong subscription calls whichever run is measuring. */
const handlers: { current: (m: { data: string }) => void } = { current: () => {} };

const ms = (us: number | null | undefined, d = 2) => fmt(us == null ? NaN : us / 1000, d);
const perK = (cpuS: number, n: number) => fmt((cpuS / n) * 1000, 3);

export const ros2Section: Section = {
  id: 'ros2',
  title: 'ROS 2: rclpy ping/pong, and the rclpy bridge',
  precheck() {
    try {
      ros2Python();
      return null;
    } catch (err) {
      return (err as Error).message;
    }
  },
  async run(ctx: BenchContext): Promise<SectionOutput> {
    const domain = 200 + (process.pid % 30);
    const big = ctx.quick ? 5000 : 60_000;
    const each = ctx.quick ? 500 : 3000;
    const settings = {
      domain,
      pingPong1kHz: big,
      perRate: each,
      rates: RATES,
      qos: 'reliable, depth 1000',
      middleware: 'rmw_fastrtps_cpp',
    };
    const echo = await pingpong(['echo', '--domain', String(domain)]);
    let bridge: Ros2Bridge | undefined;
    try {
      ctx.log(`ros2: rclpy ⇄ rclpy, ${big} messages at 1 kHz`);
      const main = await direct(domain, 1000, big);
      bridge = await Ros2Bridge.start({ domain });
      await bridge.subscribe(PONG, 'string', (m) => handlers.current(m));
      await bridge.advertise(PING, 'string', { waitMs: 10_000 });
      await warmUp(bridge);
      const rows: Row[] = [
        {
          figure: `rclpy ⇄ rclpy ping/pong, ${big} messages at 1 kHz: round trip p50 / p99 (ms), lost`,
          value: `${ms(main.p50_us, 3)} / ${ms(main.p99_us, 3)}, lost ${main.lost}`,
          baseline: 'seed 004: 197 µs (its machine)',
          target: 'no loss',
          met: main.lost === 0,
        },
      ];
      const perRate: Record<string, unknown> = {};
      for (const rate of RATES) {
        ctx.log(`ros2: ${each} messages at ${rate} Hz, bridged and direct`);
        const b = await bridged(bridge, rate, each);
        const d = await direct(domain, rate, each);
        perRate[rate] = { bridged: b, direct: d };
        rows.push({
          figure: `through the bridge at ${rate} Hz: round trip p50 / p99 (ms), lost; CPU s per 1,000 messages`,
          value: `${ms(b.p50_us)} / ${ms(b.p99_us)}, lost ${b.lost}; ${perK(b.cpu_s, each)}`,
          baseline: `rclpy direct: ${ms(d.p50_us)} / ${ms(d.p99_us)}, lost ${d.lost}; ${perK(d.cpu_s, each)}`,
          target: `added p50 ${ms(b.p50_us - (d.p50_us ?? NaN))} ms (reported)`,
          met: null,
        });
      }
      return {
        rows,
        settings,
        data: {
          pingPong1kHz: { ...main, p50_us: round(main.p50_us ?? NaN, 1) },
          perRate,
        },
      };
    } finally {
      await bridge?.close();
      await echo.child.stop();
    }
  },
};
