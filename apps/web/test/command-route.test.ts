import { describe, expect, it } from 'vitest';
import { routeCommand } from '../src/core/link/commandRoute.ts';
import { BrokerTracker } from '../src/core/link/BrokerTracker.ts';
import { ControlClaim } from '../src/core/link/ControlClaim.ts';

const enc = (s: string) => new TextEncoder().encode(s);

/** bob's claim on arm1 (logged in), with `holder` holding it. */
function claimHeldBy(holder: string | null): ControlClaim {
  const claim = new ControlClaim('arm1', { name: 'bob', enforced: true, admin: false }, () => true);
  claim.onHolder(enc(JSON.stringify({ user: holder, role: 'operator', since: 1, requests: [] })));
  return claim;
}

describe('routeCommand (docs/protocol.md § Modes, § Control)', () => {
  it('Twin: the arm, on the user’s own topic; Model: its copy; Shadow: nowhere, saying why', () => {
    const claim = claimHeldBy('bob');
    expect(routeCommand('arm1', 'twin', claim, '#000P1500T0100!', true)).toEqual({
      to: 'arm/arm1/control/bob',
    });
    expect(routeCommand('arm1', 'model', claim, '#000P1500T0100!', true).to).toBe(
      'arm/arm1-model/control/bob',
    );
    expect(routeCommand('arm1', 'shadow', claim, '#000PDST!', true)).toEqual({
      to: null,
      refused: 'not sent: Shadow mode sends no commands',
    });
  });

  it('another holder: a move is refused by name, stops and pings still go', () => {
    const claim = claimHeldBy('alice');
    expect(routeCommand('arm1', 'twin', claim, '#000P1500T0100!', true)).toEqual({
      to: null,
      refused: 'not sent: alice controls the arm',
    });
    expect(routeCommand('arm1', 'twin', claim, '#000PDST!#001PDST!', true).to).toBe(
      'arm/arm1/control/bob',
    );
    expect(routeCommand('arm1', 'twin', claim, '$PNG:1!', false).to).toBe('arm/arm1/control/bob');
  });
});

describe('BrokerTracker (docs/protocol.md § Several brokers)', () => {
  const choice = (index: number, count = 2) => ({ index, count, url: `ws://b${index}:9001` });

  it('names the broker of a list, counts moves between brokers, and says nothing for one', () => {
    const t = new BrokerTracker();
    expect(t.connectedTo(undefined)).toBe(false);
    expect(t.connectedTo(choice(0))).toBe(false); // the first connect is no move
    expect(t.inUse).toMatch(/^Broker 1 of 2/);
    expect(t.connectedTo(choice(0))).toBe(false);
    expect(t.connectedTo(choice(1))).toBe(true);
    expect(t.inUse).toMatch(/^Broker 2 of 2/);
    expect(t.moves).toBe(1);
    const one = new BrokerTracker();
    one.connectedTo(choice(0, 1));
    expect(one.inUse).toBe('');
  });
});
