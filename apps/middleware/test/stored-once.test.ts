/**
 * Stored exactly once across two middlewares (docs/cluster.md § How the middlewares share the
 * stream): a stamped report delivered twice, its copies taken by different middlewares, must
 * land on ONE InfluxDB point, whatever else each middleware stored of that millisecond. Found on
 * the NATS cluster: an arm's state report and its health report of the same ms, the state
 * report re-sent after a node was lost and taken by the other middleware, which had just stored
 * that health report: it moved the state report 1 µs later, a second copy.
 */
import { describe, expect, test } from 'vitest';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';

const T = 1_700_000_000_000; // a $TIM stamp, ms

/**
 * What InfluxDB keeps of some lines: one point per series and time, the fields of every line
 * written there merged (a field written twice keeps its last value).
 */
function influx(lines: string[]): Map<string, Map<string, string>> {
  const points = new Map<string, Map<string, string>>();
  for (const line of lines) {
    const [series = '', fields = '', time = ''] = line.split(' ');
    const key = `${series} ${time}`;
    const p = points.get(key) ?? new Map<string, string>();
    for (const kv of fields.split(',')) {
      const [k = '', v = ''] = kv.split('=');
      p.set(k, v);
    }
    points.set(key, p);
  }
  return points;
}

/** The points of servo `id` holding `field`. */
const holding = (points: Map<string, Map<string, string>>, id: string, field: string) =>
  [...points].filter(([k, p]) => k.includes(`id=${id} `) && p.has(field)).length;

const state = (ms: number, pwm: number) => `$TIM:${ms}!{#000P${pwm}!#001P${pwm}!}`;
const health = (ms: number, temp: number) => `$TIM:${ms}!#000T0${temp}V7400!#001T0${temp}V7400!`;

describe('a report taken by two middlewares is one point', () => {
  // The copy's middleware took the health report of that ms before it (either order on the first).
  for (const firstOrder of [
    ['state', 'health'],
    ['health', 'state'],
  ] as const)
    test(`first middleware: ${firstOrder.join(' then ')}; the other: health, then the state report again`, () => {
      const msg = { state: state(T, 1500), health: health(T, 45) };
      const a = new Ingest(new Metrics());
      const b = new Ingest(new Metrics());
      const lines = [
        ...firstOrder.flatMap((k) => a.handle('arm/arm1/status', msg[k], 1)),
        ...b.handle('arm/arm1/status', msg.health, 2),
        ...b.handle('arm/arm1/status', msg.state, 3),
      ];
      const points = influx(lines);
      expect(holding(points, '000', 'pwm')).toBe(1);
      expect(holding(points, '000', 'temp')).toBe(1);
    });

  // The sim's pattern (state at 50 Hz, health at 1 Hz on the same ticks: every health report
  // shares its ms with a state report); a node lost now and then: the reports sent since the last
  // acknowledgement are sent again, every copy taken by either middleware.
  test('a stream of state and health reports, the last few re-sent after each of many losses', () => {
    let seed = 7;
    const random = () => (seed = (seed * 1_103_515_245 + 12_345) % 2 ** 31) / 2 ** 31;
    const a = new Ingest(new Metrics());
    const b = new Ingest(new Metrics());
    const lines: string[] = [];
    const take = (p: string) =>
      lines.push(...(random() < 0.5 ? a : b).handle('arm/arm1/status', p, 0));
    const sent: string[] = [];
    let states = 0;
    let healths = 0;
    for (let k = 0; k < 3000; k++) {
      const ms = T + k * 20;
      const tick = [state(ms, 1000 + (k % 1000))];
      states++;
      if (k % 50 === 0) {
        tick[random() < 0.5 ? 'push' : 'unshift'](health(ms, 30 + (k % 60)));
        healths++;
      }
      sent.push(...tick);
      if (random() < 0.1) sent.push(...sent.slice(-1 - Math.floor(random() * 6)));
    }
    for (const p of sent) take(p);
    const points = influx(lines);
    for (const id of ['000', '001']) {
      expect(holding(points, id, 'pwm')).toBe(states);
      expect(holding(points, id, 'temp')).toBe(healths);
    }
  });
});
