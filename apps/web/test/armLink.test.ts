import { afterEach, beforeEach, describe, expect, it, vi } from 'vitest';
import { encodeGroup, encodePosition, pwmFromAngle } from '@armtwin/protocol';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import type { ConnectOptions } from '../src/core/link/connectOptions.ts';
import { FakeMqttClient as FakeClient } from './support/FakeMqttClient.ts';
import { defaultSettings } from '../src/core/config/settings.ts';

function setup() {
  const store = new ArmStore();
  const client = new FakeClient();
  let opts: ConnectOptions | undefined;
  const settings = {
    ...defaultSettings({ protocol: 'http:', host: 'h' }),
    username: 'op',
    password: 'pw',
  };
  const link = new ArmLink(store, settings, (url, o) => {
    expect(url).toBe('ws://h/mqtt');
    opts = o;
    return client;
  });
  link.start();
  client.emit('connect');
  const commands = () =>
    client.published.filter((p) => !p.payload.startsWith('$PNG')).map((p) => p.payload);
  return { store, client, link, opts: () => opts!, commands };
}

describe('ArmLink', () => {
  beforeEach(() => vi.useFakeTimers());
  afterEach(() => vi.useRealTimers());

  it('a tap is subscribed on the same client (now, and at each connect) and gets its messages', () => {
    const { client, link } = setup();
    const got: string[] = [];
    link.tap({
      filter: 'arm/arm1/camera/+',
      matches: (t) => t.startsWith('arm/arm1/camera/'),
      onMessage: (t) => got.push(t),
    });
    expect(client.subscribed).toContain('arm/arm1/camera/+');
    client.subscribed = [];
    client.emit('connect');
    expect(client.subscribed).toContain('arm/arm1/camera/+');
    client.emit('message', 'arm/arm1/camera/front', new Uint8Array());
    client.emit('message', 'arm/arm1/online', new TextEncoder().encode('1'));
    expect(got).toEqual(['arm/arm1/camera/front']);
  });

  it('connects with the credentials, keep-alive 60 s and reconnect 1 s, and subscribes status and online', () => {
    const { store, client, opts, link } = setup();
    expect(opts()).toMatchObject({
      username: 'op',
      password: 'pw',
      keepalive: 60,
      reconnectPeriod: 1000,
    });
    expect(store.connection).toBe('connected');
    expect(client.subscribed).toEqual([
      'arm/arm1/status',
      'arm/arm1/online',
      'arm/arm1/summary', // who holds the arm, until the holder record comes
      'arm/arm1/holder',
      'arm/arm1/audit',
      'arm/arm1/control/#',
    ]);
    link.stop();
    expect(client.ended).not.toBeNull();
  });

  it('feeds status messages into the store and reads the retained online flag', () => {
    const { store, client, link } = setup();
    client.emit(
      'message',
      'arm/arm1/status',
      new TextEncoder().encode(encodeGroup([encodePosition(0, 1600)])),
    );
    expect(store.pwm[0]).toBe(1600);
    client.emit('message', 'arm/arm1/online', new TextEncoder().encode('0'));
    expect(store.armOnline).toBe(false);
    client.emit('message', 'arm/arm1/online', new TextEncoder().encode('1'));
    expect(store.armOnline).toBe(true);
    link.stop();
  });

  it('publishes coalesced jog moves at QoS 1 and never an out-of-limit pulse', () => {
    const { client, link, commands } = setup();
    link.jog(2, 1600);
    link.jog(2, 1610);
    link.jog(2, 1620);
    expect(commands()).toEqual(['#002P1600T0100!']);
    vi.advanceTimersByTime(60);
    expect(commands()).toEqual(['#002P1600T0100!', '#002P1620T0100!']);
    link.jog(5, pwmFromAngle(-10, 1)); // gripper below 0° (closed): outside its limits
    link.jog(1, 2500); // shoulder beyond +90°
    vi.advanceTimersByTime(200);
    expect(commands()).toHaveLength(2);
    expect(client.published.every((p) => p.topic === 'arm/arm1/control' && p.qos === 1)).toBe(true);
    link.stop();
  });

  it('hears its own command back as that command, however late; the same from another as a new one', () => {
    const { store, client, link, commands } = setup();
    const enc = (s: string) => new TextEncoder().encode(s);
    client.emit('message', 'arm/arm1/status', enc(encodeGroup([encodePosition(2, 1500)])));
    link.jog(2, 1900);
    const [sent] = commands();
    const j = store.predictor.joint(2)!;
    const course = () => ({ start: j.start, from: j.from, v: j.vCmd });
    const before = course();
    expect(before.v).toBeGreaterThan(0);
    // The echo comes back 1.5 s later (a loaded page): still the command already drawn.
    const t = performance.now();
    const clock = vi.spyOn(performance, 'now').mockReturnValue(t + 1500);
    client.emit('message', 'arm/arm1/control', enc(sent!));
    expect(course()).toEqual(before);
    // The same bytes again are someone's second command: the course starts over from there.
    client.emit('message', 'arm/arm1/control', enc(sent!));
    expect(course()).not.toEqual(before);
    clock.mockRestore();
    link.stop();
  });

  it('emergency stop publishes #255PDST! at QoS 1 and drops pending jogs', () => {
    const { client, link, commands, store } = setup();
    link.jog(0, 1600);
    link.jog(0, 1700); // pending
    expect(link.emergencyStop()).toBe(true);
    vi.advanceTimersByTime(500);
    expect(commands()).toEqual(['#000P1600T0100!', '#255PDST!']);
    expect(client.published.find((p) => p.payload === '#255PDST!')?.qos).toBe(1);
    expect(store.commandedPwm[0]).toBeNaN();
    link.stop();
  });

  it('pings every second while connected and measures the round trip', () => {
    const { client, store, link } = setup();
    vi.advanceTimersByTime(1000);
    const ping = client.published.find((p) => p.payload.startsWith('$PNG:'));
    expect(ping).toBeDefined();
    client.emit('message', 'arm/arm1/status', new TextEncoder().encode(ping!.payload));
    expect(store.ping.echoed).toBe(1);
    expect(store.ping.rttMs).toBeGreaterThanOrEqual(0);
    link.stop();
  });

  it('ignores what a stopped client still delivers: the previous arm never shows as the next', () => {
    const { store, client, link } = setup();
    link.stop();
    store.resetArm();
    // Bytes already in the old socket arrive after the page switched arms.
    client.emit(
      'message',
      'arm/arm1/status',
      new TextEncoder().encode(encodeGroup([encodePosition(0, 1500)])),
    );
    client.emit('error', new Error('late'));
    expect(Number.isNaN(store.pwm[0])).toBe(true);
    expect(store.connection).toBe('idle');
  });

  it('sends $KMS with the commanded pose', () => {
    const { link, commands, store } = setup();
    link.moveTo(180, 100, 80, undefined, [1700, 1300, 1200, 900]);
    expect(commands()).toEqual(['$KMS:180,100,80,1500!']);
    expect(Array.from(store.commandedPwm.slice(0, 4))).toEqual([1700, 1300, 1200, 900]);
    link.stop();
  });
});
