import { EventEmitter } from 'node:events';
import type { MqttClient } from 'mqtt';
import { afterEach, beforeEach, describe, expect, test, vi } from 'vitest';
import { retryRefusedSubscriptions } from '../src/resubscribe.ts';

type Cb = (err: Error | null, subs?: unknown[], packet?: { granted: number[] }) => void;

/** A client whose broker refuses (0x80) each filter in `refuse` for its first `times` asks. */
function fakeClient(refuse: string[], times: number) {
  const c = new EventEmitter() as EventEmitter & {
    connected: boolean;
    disconnecting: boolean;
    asked: string[][];
    subscribe: (topics: string[] | Record<string, unknown>, opts: object | Cb, cb?: Cb) => unknown;
    qos: Map<string, number>;
  };
  c.connected = true;
  c.disconnecting = false;
  c.asked = [];
  c.qos = new Map();
  const left = new Map(refuse.map((t) => [t, times]));
  c.subscribe = (what, opts, cb) => {
    // A list with options, or mqtt.js's resubscription: a map of filter → options.
    const map = Array.isArray(what) ? null : what;
    const topics = map ? Object.keys(map).filter((k) => k !== 'resubscribe') : (what as string[]);
    for (const t of topics)
      c.qos.set(t, map ? (map[t] as { qos: number }).qos : (opts as { qos: number }).qos);
    const done: Cb = cb ?? (typeof opts === 'function' ? (opts as Cb) : () => {});
    c.asked.push(topics);
    const granted = topics.map((t) => {
      const n = left.get(t) ?? 0;
      if (n > 0) left.set(t, n - 1);
      return n > 0 ? 0x80 : 1;
    });
    const err = granted.some((g) => g & 0x80)
      ? new Error('Subscribe error: Unspecified error')
      : null;
    queueMicrotask(() =>
      done(
        err,
        topics.map((topic, i) => ({ topic, qos: granted[i] })),
        { granted },
      ),
    );
    return c;
  };
  return c;
}

describe('a subscription the broker refused is asked for again', () => {
  beforeEach(() => void vi.useFakeTimers());
  afterEach(() => void vi.useRealTimers());

  test('only the refused filters, every retry period, until granted; the part hears the first answer', async () => {
    const c = fakeClient(['arm/a1/control'], 2);
    const retried: string[][] = [];
    retryRefusedSubscriptions(c as unknown as MqttClient, 1000, (t) => retried.push(t));
    const answers: (string | null)[] = [];
    (c as unknown as MqttClient).subscribe(['arm/a1/control', 'arm/a1/sim'], { qos: 1 }, (err) =>
      answers.push(err?.message ?? null),
    );
    await vi.advanceTimersByTimeAsync(0);
    expect(answers).toEqual(['Subscribe error: Unspecified error']);
    await vi.advanceTimersByTimeAsync(5000);
    expect(c.asked).toEqual([
      ['arm/a1/control', 'arm/a1/sim'],
      ['arm/a1/control'],
      ['arm/a1/control'],
    ]);
    expect(retried).toEqual([['arm/a1/control'], ['arm/a1/control']]);
    expect(answers).toHaveLength(1);
  });

  test('a lost connection ends the retries (the part subscribes again on connect)', async () => {
    const c = fakeClient(['arm/a1/control'], 100);
    retryRefusedSubscriptions(c as unknown as MqttClient, 1000);
    (c as unknown as MqttClient).subscribe('arm/a1/control', { qos: 1 });
    await vi.advanceTimersByTimeAsync(1500);
    expect(c.asked).toHaveLength(2);
    c.emit('close');
    await vi.advanceTimersByTimeAsync(5000);
    expect(c.asked).toHaveLength(2);
  });

  test("mqtt.js's own resubscription after a reconnect is retried too, each filter at its QoS", async () => {
    const c = fakeClient(['arm/a1/holder'], 1);
    retryRefusedSubscriptions(c as unknown as MqttClient, 1000);
    c.qos.clear();
    const resubscribe = {
      'arm/a1/status': { qos: 0 },
      'arm/a1/holder': { qos: 1 },
      resubscribe: true,
    };
    (c as unknown as MqttClient).subscribe(resubscribe as never);
    await vi.advanceTimersByTimeAsync(1500);
    expect(c.asked).toEqual([['arm/a1/status', 'arm/a1/holder'], ['arm/a1/holder']]);
    expect(c.qos.get('arm/a1/holder')).toBe(1);
  });
});
