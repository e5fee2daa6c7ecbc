/**
 * The fleet link's MQTT edge with a stand-in client: the same connect options as the arm link
 * (one factory, the protocol's defaults), and every piece of input it rejects counted — the
 * reader's drops by kind, bad announcements, bad feedback — while the good input still counts.
 */
import { describe, expect, it } from 'vitest';
import {
  encodeGroup,
  encodeHealth,
  MQTT_CONNECT_TIMEOUT_MS,
  MQTT_KEEPALIVE_S,
  MQTT_RECONNECT_MS,
} from '@armtwin/protocol';
import { FleetLink, type FleetMqtt } from '../src/core/robots/FleetLink.ts';
import type { ConnectOptions } from '../src/core/link/connectOptions.ts';
import { defaultSettings } from '../src/core/config/settings.ts';

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
  subscribe() {
    return this;
  }
  unsubscribe() {
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

  it("counts what its reader drops, by kind, and still takes another arm's good health frames", () => {
    const { client, fleet } = setup();
    client.message('arm/arm2/online', '1');
    client.message(
      'arm/arm2/status',
      `${encodeGroup([encodeHealth(0, 41, 7400), encodeHealth(1, 42, 7400)])}V junk!#001PX!`,
    );
    expect(fleet.counters.dropped).toBe(2);
    expect(fleet.counters.droppedByKind.junk).toBe(1);
    expect(fleet.counters.droppedByKind.malformed).toBe(1);
    expect(fleet.firstError.junk).toContain('V junk!');
    expect(fleet.state.get('arm2')?.online).toBe(true);
    expect(fleet.state.get('arm2')?.level).toBe('normal');
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
