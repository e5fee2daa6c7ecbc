/**
 * The fleet link's MQTT edge with a stand-in client: the same connect options as the arm link
 * (one factory, the protocol's defaults), what it subscribes (every arm's summary, never another
 * arm's status), and every piece of input it rejects counted by kind — bad summaries, alerts,
 * announcements, feedback — while the good input still counts.
 */
import { describe, expect, it } from 'vitest';
import {
  MQTT_CONNECT_TIMEOUT_MS,
  MQTT_KEEPALIVE_S,
  MQTT_RECONNECT_MS,
  type ArmSummary,
} from '@armtwin/protocol';
import { FleetLink, type FleetMqtt } from '../src/core/robots/FleetLink.ts';
import type { ConnectOptions } from '../src/core/link/connectOptions.ts';
import { defaultSettings } from '../src/core/config/settings.ts';

const SUMMARY: ArmSummary = {
  t: 1,
  state: 'moving',
  why: '',
  health: 'normal',
  alarm: '',
  holder: 'alice',
  joints: [{ id: 0, deg: 10, min: -90, max: 90 }],
  error: null,
};

class FakeClient implements FleetMqtt {
  handlers = new Map<string, ((...args: never[]) => void)[]>();
  on(event: string, cb: (...args: never[]) => void) {
    this.handlers.set(event, [...(this.handlers.get(event) ?? []), cb]);
    return this;
  }
  emit(event: string, ...args: unknown[]) {
    for (const cb of this.handlers.get(event) ?? []) (cb as (...a: unknown[]) => void)(...args);
  }
  message(topic: string, text: string) {
    this.emit('message', topic, new TextEncoder().encode(text));
  }
  subscribed: string[] = [];
  subscribe(topics: string[]) {
    this.subscribed.push(...topics);
    return this;
  }
  unsubscribe(topics: string[]) {
    this.subscribed = this.subscribed.filter((t) => !topics.includes(t));
    return this;
  }
  publish() {
    return this;
  }
  end() {
    return this;
  }
}

function setup() {
  const client = new FakeClient();
  let opts: ConnectOptions | undefined;
  const settings = { ...defaultSettings({ protocol: 'http:', host: 'h' }), username: 'v' };
  const fleet = new FleetLink(settings, (_url, o) => {
    opts = o;
    return client;
  });
  fleet.start();
  client.emit('connect');
  return { client, fleet, opts: () => opts };
}

describe('FleetLink', () => {
  it("connects with the protocol's keep-alive, reconnect and connect timeout", () => {
    const { opts } = setup();
    expect(opts()).toMatchObject({
      username: 'v',
      keepalive: MQTT_KEEPALIVE_S,
      reconnectPeriod: MQTT_RECONNECT_MS,
      connectTimeout: MQTT_CONNECT_TIMEOUT_MS,
      clean: true,
    });
    expect(opts()?.clientId).toMatch(/^armtwin-fleet-[0-9a-f]+$/);
  });

  it("follows every arm's summary and alerts, never another arm's status, whatever the fleet", () => {
    const { client, fleet } = setup();
    expect(client.subscribed).toEqual(
      expect.arrayContaining(['arm/+/online', 'arm/+/profile', 'arm/+/summary', 'arm/+/alert']),
    );
    for (let i = 1; i <= 50; i++) client.message(`arm/arm${i}/online`, '1');
    fleet.select('arm37');
    expect(client.subscribed.filter((t) => t.endsWith('/status'))).toEqual([]);
    client.message(
      'arm/arm37/summary',
      JSON.stringify({ ...SUMMARY, health: 'critical', alarm: 'servo 002: 90 °C' }),
    );
    expect(fleet.state.get('arm37')).toMatchObject({
      level: 'critical',
      alarm: 'servo 002: 90 °C',
      holder: 'alice',
      state: 'moving',
    });
    client.message('arm/arm37/summary', '');
    expect(fleet.state.get('arm37')).toMatchObject({ level: 'unknown', state: null });
  });

  it('counts a bad summary and a bad alert by kind, keeps the first reason, and still takes good ones', () => {
    const { client, fleet } = setup();
    client.message('arm/arm2/summary', JSON.stringify(SUMMARY));
    client.message('arm/arm2/summary', '{"t":1}');
    client.message('arm/arm2/alert', 'not json');
    expect(fleet.counters.badSummaries).toBe(1);
    expect(fleet.counters.badAlerts).toBe(1);
    expect(fleet.firstError.summary).toBe('arm/arm2/summary: state: unknown');
    expect(fleet.state.get('arm2')).toMatchObject({ level: 'normal', holder: 'alice' });
    client.message(
      'arm/arm2/alert',
      JSON.stringify({
        at: 1,
        kind: 'thermal-warning',
        id: '002',
        tempC: 50,
        predictedC: 40,
        excessCPerS: 0.5,
        secondsToLimit: 20,
        detail: 'servo 002 heats',
      }),
    );
    expect(fleet.state.get('arm2')?.warnings).toEqual({ '002': 'servo 002 heats' });
  });

  it('counts a bad announcement and bad feedback', () => {
    const { client, fleet } = setup();
    client.message('arm/arm2/profile', '{"format":"nope"}');
    client.message(`arm/${fleet.selectedArm}/feedback`, 'not json');
    expect(fleet.counters.badProfiles).toBe(1);
    expect(fleet.counters.badFeedback).toBe(1);
    expect(fleet.profiles.size).toBe(0);
  });
});
