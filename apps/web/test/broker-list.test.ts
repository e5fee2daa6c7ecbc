/**
 * Several brokers in the page: the connection settings take an ordered list, and the arm link
 * says which broker it uses and forgets the other broker's holder after a move (never
 * re-claiming control on the page's behalf).
 */
import { describe, expect, it } from 'vitest';
import type { BrokerChoice } from '@armtwin/link';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { ArmLink } from '../src/core/link/ArmLink.ts';
import { FakeMqttClient } from './support/FakeMqttClient.ts';
import {
  applyQuery,
  brokerListProblem,
  defaultSettings,
  validateSettings,
} from '../src/core/config/settings.ts';

const base = defaultSettings({ protocol: 'http:', host: 'h' });

describe('broker list in the settings', () => {
  it('takes one ws URL or an ordered comma-separated list of them', () => {
    expect(brokerListProblem('ws://a:9001/mqtt')).toBeNull();
    expect(brokerListProblem('ws://a:9001/mqtt, wss://b.example/mqtt')).toBeNull();
    const q = `?broker=${encodeURIComponent('ws://a:9001,ws://b:9002')}`;
    expect(applyQuery(base, q).brokerUrl).toBe('ws://a:9001,ws://b:9002');
  });

  it('refuses a bad list with a message naming the entry, and keeps the default from a bad query', () => {
    expect(brokerListProblem('ws://a:9001,mqtt://b:1883')).toMatch(
      /must start with ws:\/\/ or wss:\/\/ \(“mqtt:\/\/b:1883”\)/,
    );
    expect(brokerListProblem('ws://a:9001,,ws://b:1')).toMatch(/broker 2 of 3 is empty/);
    expect(validateSettings({ ...base, brokerUrl: 'ws://a:1,ws://a:1' })).toMatch(/listed twice/);
    expect(applyQuery(base, '?broker=ws://a:1,nope').brokerUrl).toBe(base.brokerUrl);
  });
});

/** A client on a list of brokers: `brokers.choice` is settable. */
class ListClient extends FakeMqttClient {
  brokers: { choice: BrokerChoice } = { choice: { index: 0, count: 2, url: 'ws://a:1' } };
}

describe('ArmLink on a list of brokers', () => {
  it('says which broker it uses, and after a move forgets the holder and claims nothing', () => {
    const client = new ListClient();
    const link = new ArmLink(
      new ArmStore(),
      { ...base, brokerUrl: 'ws://a:1,ws://b:2' },
      () => client,
    );
    link.start(undefined, {}, { name: 'ann', enforced: true, admin: false });
    client.emit('connect');
    expect(link.brokerInUse).toBe('Broker 1 of 2: ws://a:1');
    const holder = (user: string | null) =>
      client.emit(
        'message',
        'arm/arm1/holder',
        new TextEncoder().encode(JSON.stringify({ user, since: 1, requests: [] })),
      );
    holder('ann');
    expect(link.control.holding).toBe(true);

    client.emit('close');
    client.brokers.choice = { index: 1, count: 2, url: 'ws://b:2' };
    const claimsBefore = client.published.filter((p) => p.topic.includes('/claim/')).length;
    client.emit('connect');
    expect(link.brokerInUse).toBe('Broker 2 of 2: ws://b:2');
    expect(link.brokerMoves).toBe(1);
    expect(link.control.holding).toBe(false); // the other broker's word is forgotten
    holder(null); // nobody holds the arm on the new broker: the page does not take it by itself
    const claims = client.published.filter((p) => p.topic.includes('/claim/'));
    expect(claims.length).toBe(claimsBefore);
  });

  it('says nothing about brokers with one', () => {
    const client = new ListClient();
    client.brokers.choice = { index: 0, count: 1, url: 'ws://a:1' };
    const link = new ArmLink(new ArmStore(), base, () => client);
    link.start();
    client.emit('connect');
    expect(link.brokerInUse).toBe('');
  });
});
