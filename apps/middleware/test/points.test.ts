import { describe, expect, test } from 'vitest';
import { Ingest } from '../src/ingest.ts';
import { Metrics } from '../src/metrics.ts';
import { SeriesClock, servoId } from '../src/points.ts';

const T = 1_700_000_000_000; // a $TIM stamp, ms
const setup = () => {
  const metrics = new Metrics();
  return { metrics, ingest: new Ingest(metrics) };
};

describe('frames → points (PROTOCOL §6)', () => {
  test('position: servo,arm,id(3 digits) pwm int + angle float, time from $TIM in µs', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/status', `$TIM:${T}!#001P1600!#000P1500!`, 5)).toEqual([
      `servo,arm=arm1,id=001 pwm=1600i,angle=13.5 ${T * 1000}`,
      `servo,arm=arm1,id=000 pwm=1500i,angle=0 ${T * 1000}`,
    ]);
  });

  test('health: temp °C and volt = mV/1000', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/a-2/status', `$TIM:${T}!#002T045V7400!`, 5)).toEqual([
      `servo,arm=a-2,id=002 temp=45,volt=7.4 ${T * 1000}`,
    ]);
  });

  test('a group keeps its valid frames; frames without $TIM get the arrival time', () => {
    const { ingest, metrics } = setup();
    const lines = ingest.handle('arm/arm1/status', '{#000P1500!#001PXXXX!#002P2500!}', 42);
    expect(lines).toEqual([
      'servo,arm=arm1,id=000 pwm=1500i,angle=0 42000',
      'servo,arm=arm1,id=002 pwm=2500i,angle=135 42000',
    ]);
    expect(metrics.rejected).toEqual({ malformed: 1 });
  });

  test('the $TIM stamp of one message does not leak into the next', () => {
    const { ingest } = setup();
    ingest.handle('arm/arm1/status', `$TIM:${T}!#000P1500!`, 1);
    expect(ingest.handle('arm/arm1/status', '#000P1501!', T + 7)).toEqual([
      expect.stringMatching(new RegExp(` ${(T + 7) * 1000}$`)),
    ]);
  });

  test('a frame split across two messages of one topic is joined', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/status', '#000P15', 1)).toEqual([]);
    expect(ingest.handle('arm/arm1/status', '00!', 2)).toEqual([
      'servo,arm=arm1,id=000 pwm=1500i,angle=0 2000',
    ]);
  });

  test('moves on control become command points; a group with a bad frame is not stored', () => {
    const { ingest, metrics } = setup();
    expect(ingest.handle('arm/arm1/control', `$TIM:${T}!#003P1000T0500!`, 1)).toEqual([
      `command,arm=arm1,id=003 pwm=1000i,angle=-67.5,ms=500i ${T * 1000}`,
    ]);
    expect(ingest.handle('arm/arm1/control', '{#000P1500T1000!#001P9999T1000!}', 1)).toEqual([]);
    expect(metrics.rejected).toMatchObject({ 'out-of-range': 1, 'group-not-executed': 1 });
  });

  test('$KMS request and $KMS:c! result make one ik point at the result time', () => {
    const { ingest } = setup();
    expect(ingest.handle('arm/arm1/control', '$KMS:-12.5,180,40,-90,800!', 1)).toEqual([]);
    expect(ingest.handle('arm/arm1/status', `$TIM:${T}!$KMS:2!`, 2)).toEqual([
      `ik,arm=arm1 code=2i,x=-12.5,y=180,z=40,a=-90 ${T * 1000}`,
    ]);
    // a result with no request seen: code only; a request superseded unanswered: target only
    expect(ingest.handle('arm/arm1/status', '$KMS:0!', T + 3)).toEqual([
      `ik,arm=arm1 code=0i ${(T + 3) * 1000}`,
    ]);
    ingest.handle('arm/arm1/control', '$KMS:1,2,3,100!', T + 4);
    expect(ingest.handle('arm/arm1/control', '$KMS:4,5,6,100!', T + 5)).toEqual([
      `ik,arm=arm1 x=1,y=2,z=3 ${(T + 4) * 1000}`,
    ]);
  });

  test('malformed input, wrong-direction frames and foreign topics are counted, never stored', () => {
    const { ingest, metrics } = setup();
    expect(ingest.handle('arm/arm1/status', 'garbage!#000P1500T100!#00!{}}', 1)).toEqual([]);
    expect(ingest.handle('arm/arm1/control', '#000P1500!', 1)).toEqual([]);
    expect(ingest.handle('foo/bar', '#000P1500!', 1)).toEqual([]);
    expect(metrics.rejected).toMatchObject({
      junk: 1,
      'wrong-direction': 2,
      malformed: 1,
      'unexpected-group-end': 1,
      'bad-topic': 1,
    });
    expect(metrics.pointsProduced).toBe(0);
  });

  test('servo ids are always three digits', () => {
    expect([0, 7, 42, 254].map(servoId)).toEqual(['000', '007', '042', '254']);
  });
});

describe('unique timestamps per series', () => {
  test('a 1 kHz stream whose stamps collide or come 2 per ms keeps every point', () => {
    const clock = new SeriesClock();
    const seen = new Map<string, Set<number>>();
    // 10 s at 1 kHz, 6 servos; every 10th payload repeats the previous stamp, some ms carry two
    let stamp = T;
    for (let k = 0; k < 10_000; k++) {
      if (k % 10 !== 0) stamp += k % 7 === 0 ? 0 : 1;
      for (let id = 0; id < 6; id++) {
        const s = `servo,arm=arm1,id=${servoId(id)}`;
        const t = clock.next(s, stamp * 1000);
        const set = seen.get(s) ?? new Set();
        expect(set.has(t)).toBe(false);
        set.add(t);
        seen.set(s, set);
      }
    }
    for (const set of seen.values()) expect(set.size).toBe(10_000);
    expect(clock.bumped).toBeGreaterThan(0);
  });

  test('series are independent, and a later stamp is used as is', () => {
    const c = new SeriesClock();
    expect([
      c.next('a', 1000),
      c.next('a', 1000),
      c.next('b', 1000),
      c.next('a', 999),
      c.next('a', 5000),
    ]).toEqual([1000, 1001, 1000, 1002, 5000]);
  });

  test('through the ingest: two payloads with the same $TIM never share a time', () => {
    const { ingest, metrics } = setup();
    const a = ingest.handle('arm/arm1/status', `$TIM:${T}!{#000P1500!#001P1500!}`, 1);
    const b = ingest.handle('arm/arm1/status', `$TIM:${T}!{#000P1501!#001P1501!}`, 1);
    const times = [...a, ...b].map((l) => {
      const [series = '', , time = ''] = l.split(' ');
      return `${series}@${time}`;
    });
    expect(new Set(times).size).toBe(4);
    expect(metrics.timestampsBumped).toBe(2);
  });

  // docs/protocol.md § Several brokers: a QoS 1 report may come twice across a broker move.
  const state = (ms: number, pwm: number) => `$TIM:${ms}!{#000P${pwm}!#001P${pwm}!}`;
  const times = (lines: string[]) => lines.map((l) => Number(l.split(' ')[2]));

  test('the same stamped report received again overwrites its first copy, not a new point', () => {
    const { ingest, metrics } = setup();
    const first = ingest.handle('arm/arm1/status', state(T, 1500), 1);
    const again = ingest.handle('arm/arm1/status', state(T, 1500), 2);
    expect(again).toEqual(first);
    expect(metrics.timestampsBumped).toBe(0);
  });

  // Found on a NATS cluster (tests/integration/cluster-nats.test.ts): a state report, another
  // position of the servo stamped in the same ms (a reply to a read), then the state report
  // delivered again was bumped past that point, a second copy 1–2 µs after the first. (A health
  // report of that ms has a clock of its own and is never in the way: stored-once.test.ts.)
  test('a report received again after another point of its series in the same ms is still one point', () => {
    const { ingest, metrics } = setup();
    const first = ingest.handle('arm/arm1/status', state(T, 1500), 1);
    ingest.handle('arm/arm1/status', `$TIM:${T}!#000P1510!#001P1510!`, 2);
    ingest.handle('arm/arm1/status', `$TIM:${T}!#000T045V7400!#001T045V7400!`, 3);
    expect(ingest.handle('arm/arm1/status', state(T, 1500), 4)).toEqual(first);
    expect(metrics.timestampsBumped).toBe(2); // the read positions only
  });

  test('a report redelivered late, behind newer ones, keeps its own time (no extra point)', () => {
    const { ingest } = setup();
    const old = ingest.handle('arm/arm1/status', state(T, 1500), 1);
    ingest.handle('arm/arm1/status', state(T + 20, 1510), 2);
    ingest.handle('arm/arm1/status', state(T + 40, 1520), 3);
    expect(ingest.handle('arm/arm1/status', state(T, 1500), 4)).toEqual(old);
    // one that never came before lands where it belongs, and the stream goes on after it
    expect(times(ingest.handle('arm/arm1/status', state(T + 10, 1505), 5))).toEqual([
      (T + 10) * 1000,
      (T + 10) * 1000,
    ]);
    expect(times(ingest.handle('arm/arm1/status', state(T + 60, 1530), 6))).toEqual([
      (T + 60) * 1000,
      (T + 60) * 1000,
    ]);
  });

  test('unstamped reports are never taken for repeats: the same values in one ms stay two points', () => {
    const { ingest } = setup();
    const a = ingest.handle('arm/arm1/status', '{#000P1500!}', T);
    const b = ingest.handle('arm/arm1/status', '{#000P1500!}', T);
    expect(times([...a, ...b])).toEqual([T * 1000, T * 1000 + 1]);
  });
});
