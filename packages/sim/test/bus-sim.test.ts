/**
 * The simulator as a servo bus (`BusSimCore`), driven by the bus client as a host would: the
 * profile's ids answer from the home pose, goals are reached at the speed written, and the
 * faults show on the bus (a stalled shaft stays put and warms, overheat and undervolt read
 * back, and torque drops where the servo's own protection says so).
 */
import { describe, expect, test } from 'vitest';
import { createBusClient, type BusResult } from '@armtwin/servo-bus';
import { BusSimCore, loadSimProfile } from '../src/index.ts';

const profile = loadSimProfile('armtwin5').profile;
const ids = profile.servos.map((s) => s.id);

function rig(
  protocol: 'dynamixel' | 'feetech',
  faults: ConstructorParameters<typeof BusSimCore>[0]['faults'] = [],
) {
  let now = 1000;
  const sim = new BusSimCore({ protocol, profile, faults }, now);
  const client = createBusClient({ protocol, servos: ids.map((id) => ({ id })) });
  const ask = (bytes: Uint8Array): BusResult | undefined => {
    const reply = sim.feed(bytes, now);
    return client.feed(reply)[0] ?? client.expire();
  };
  const after = (ms: number) => {
    now += ms;
    sim.advance(now);
  };
  return { sim, client, ask, after };
}

describe.each(['dynamixel', 'feetech'] as const)('the simulated %s bus', (protocol) => {
  test("answers for the profile's ids at home and moves at the speed written", () => {
    const r = rig(protocol);
    for (const id of ids) expect(r.ask(r.client.ping(id))).toMatchObject({ found: true });
    expect(r.ask(r.client.ping(9))).toMatchObject({ found: false });
    r.ask(r.client.setTorque(true));
    r.ask(r.client.writeGoals([{ id: 1, degrees: 45 }], { speedDegPerS: 90 }));
    r.after(250);
    const mid = r.ask(r.client.readPositions());
    expect(mid?.kind === 'positions' && mid.servos[1]!.degrees).toBeCloseTo(22.5, 0);
    r.after(500);
    const end = r.ask(r.client.readPositions());
    expect(end?.kind === 'positions' && end.servos[1]!.degrees).toBeCloseTo(45, 1);
  });

  test('faults show on the bus', () => {
    const r = rig(protocol, [
      { fault: 'stall', id: 2 },
      { fault: 'overheat', id: 3, celsius: 90 },
      { fault: 'undervolt', mv: 5000 },
    ]);
    r.ask(r.client.setTorque(true, [2]));
    r.ask(r.client.writeGoals([{ id: 2, degrees: 30 }], { speedDegPerS: 90 }));
    r.after(1000);
    const p = r.ask(r.client.readPositions());
    expect(p?.kind === 'positions' && p.servos[2]!.degrees).toBe(0);
    const h = r.ask(r.client.readHealth());
    if (h?.kind !== 'health') throw new Error('no health');
    expect(h.servos[2]!.temperatureC).toBe(65);
    expect(h.servos[3]!.temperatureC).toBe(90);
    expect(h.servos[3]!.status.problems.length).toBeGreaterThan(0);
    expect(h.servos[0]!.voltageV).toBeCloseTo(5, 1);
    r.sim.apply({ fault: 'clear' });
    const cleared = r.ask(r.client.readHealth());
    expect(cleared?.kind === 'health' && cleared.servos[3]!.temperatureC).toBe(25);
  });
});
