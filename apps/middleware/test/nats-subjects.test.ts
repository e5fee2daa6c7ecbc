import { describe, expect, test } from 'vitest';
import { subscriptionTopics } from '../src/mqtt.ts';
import { consumerConfig } from '../src/nats-intake.ts';
import { subjectToTopic, topicToSubject } from '../src/nats-subjects.ts';

describe('MQTT topics ⇄ NATS subjects (as nats-server converts them)', () => {
  test.each([
    ['arm/arm1/status', 'arm.arm1.status'],
    ['arm/+/control/+', 'arm.*.control.*'],
    ['arm/#', 'arm.>'],
    // A user name may hold a dot: one topic level, written `//` in NATS.
    ['arm/arm1/control/alice.b', 'arm.arm1.control.alice//b'],
    // Empty levels (nats-server's own examples).
    ['foo//bar', 'foo./.bar'],
    ['/foo', '/.foo'],
    ['foo/', 'foo./'],
  ])('%s ⇄ %s', (topic, subject) => {
    expect(topicToSubject(topic)).toBe(subject);
    if (!/[+#]/.test(topic)) expect(subjectToTopic(subject)).toBe(topic);
  });

  test('a topic NATS cannot carry is refused by name', () => {
    expect(() => topicToSubject('arm/a b/status')).toThrow(/cannot carry.*"arm\/a b\/status"/);
  });
});

describe("the middlewares' shared consumer", () => {
  test('takes exactly the topics the middleware subscribes to over MQTT, from MQTT’s message stream', () => {
    const c = consumerConfig({ consumer: 'armtwin-middleware', ackWaitMs: 5000 });
    expect(c.filter_subjects).toEqual(
      subscriptionTopics('').map((t) => `$MQTT.msgs.${topicToSubject(t)}`),
    );
    expect(c.filter_subjects).toContain('$MQTT.msgs.arm.*.status');
    expect(c).toMatchObject({ durable_name: 'armtwin-middleware', ack_policy: 'explicit' });
    expect(c.ack_wait).toBe(5_000_000_000); // nanoseconds
  });
});
