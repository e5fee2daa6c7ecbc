import { describe, expect, it } from 'vitest';
import {
  BrokerFailover,
  describeBroker,
  parseBrokerList,
  redactBrokerUrl,
} from '../src/brokers.ts';

describe('parseBrokerList', () => {
  it('reads one URL or an ordered, comma-separated list', () => {
    expect(parseBrokerList('mqtt://127.0.0.1:1883')).toEqual(['mqtt://127.0.0.1:1883']);
    expect(parseBrokerList(' mqtt://lan:1883 , mqtts://remote.example:8883 ')).toEqual([
      'mqtt://lan:1883',
      'mqtts://remote.example:8883',
    ]);
    expect(parseBrokerList('/mqtt,ws://other:9001/mqtt', true)).toEqual([
      '/mqtt',
      'ws://other:9001/mqtt',
    ]);
  });

  it.each([
    ['', /no broker URL/],
    ['mqtt://a:1883,,mqtt://b:1883', /broker 2 of 3 is empty/],
    ['mqtt://a:1883,mqtt://a:1883', /broker 2 of 2 \(mqtt:\/\/a:1883\) is listed twice/],
    ['mqtt://a:1883,not a url', /broker 2 of 2 is not a URL: "not a url"/],
    ['http://a:80', /scheme "http:"/],
    ['/mqtt', /not a URL/],
  ])('refuses %j with a clear message', (text, message) => {
    expect(() => parseBrokerList(text)).toThrow(message);
  });

  it('hides a password in what it shows', () => {
    expect(redactBrokerUrl('wss://op:s3cret@host:8884/mqtt')).toBe('wss://op:***@host:8884/mqtt');
    expect(describeBroker({ index: 1, count: 2, url: 'ws://b:9001' })).toBe(
      'Broker 2 of 2: ws://b:9001',
    );
  });
});

describe('BrokerFailover', () => {
  const urls = ['mqtt://lan:1883', 'mqtt://remote:1883'];

  it('starts on the first, moves to the next when it is lost, and says so once', () => {
    const f = new BrokerFailover(urls);
    expect(f.url).toBe(urls[0]);
    expect(f.connected()).toMatchObject({ from: null, to: { index: 0 }, reason: 'start' });
    f.closed();
    expect(f.url).toBe(urls[1]);
    expect(f.connected()).toMatchObject({ from: { index: 0 }, to: { index: 1 }, reason: 'lost' });
    expect(f.moves).toBe(1);
    expect(describeBroker(f.choice)).toBe('Broker 2 of 2: mqtt://remote:1883');
  });

  it('wraps round the list while no broker answers', () => {
    const f = new BrokerFailover([...urls, 'mqtt://third:1883']);
    const tried = [f.url];
    for (let i = 0; i < 4; i++) {
      f.closed();
      tried.push(f.url);
    }
    expect(tried.map((u) => u.split('//')[1])).toEqual([
      'lan:1883',
      'remote:1883',
      'third:1883',
      'lan:1883',
      'remote:1883',
    ]);
  });

  it('a reconnect to the same broker is no move', () => {
    const f = new BrokerFailover(['mqtt://only:1883']);
    f.connected();
    f.closed();
    expect(f.url).toBe('mqtt://only:1883');
    expect(f.connected()).toBeNull();
    expect(f.probing).toBe(false);
  });

  it('on a fall-back, goes back to the first after it answered returnAfterProbes in a row', () => {
    const f = new BrokerFailover(urls, { returnAfterProbes: 2 });
    f.connected();
    expect(f.probing).toBe(false);
    f.closed();
    f.connected();
    expect(f.probing).toBe(true);
    expect(f.probed(true)).toBe(false);
    expect(f.probed(false)).toBe(false); // not in a row: counting starts again
    expect(f.probed(true)).toBe(false);
    expect(f.probed(true)).toBe(true);
    f.closed(); // the caller drops its connection
    expect(f.url).toBe(urls[0]);
    expect(f.connected()).toMatchObject({ to: { index: 0 }, reason: 'first-back' });
    expect(f.probing).toBe(false);
    expect(f.moves).toBe(2);
  });

  it('if the first fails again on the way back, the next attempt is the fall-back', () => {
    const f = new BrokerFailover(urls, { returnAfterProbes: 1 });
    f.connected();
    f.closed();
    f.connected();
    expect(f.probed(true)).toBe(true);
    f.closed();
    expect(f.url).toBe(urls[0]);
    f.closed(); // the first refused the attempt after all
    expect(f.url).toBe(urls[1]);
    expect(f.connected()).toBeNull(); // still on the fall-back: no move to log
    expect(f.probing).toBe(true);
  });

  it('probes nothing while on the first or while disconnected', () => {
    const f = new BrokerFailover(urls);
    expect(f.probed(true)).toBe(false);
    f.connected();
    f.closed();
    expect(f.probing).toBe(false);
    expect(f.probed(true)).toBe(false);
  });
});
