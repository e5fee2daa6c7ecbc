/**
 * The floor at the controller (docs/protocol.md, "The floor"): the simulator refuses a move, a
 * group or a `$KMS` whose goal pose puts the hand or a joint below the floor, with `$ERR:floor …`
 * (or `$KMS:1!`), counts it and moves nothing; an arm already below it may still climb out.
 * Both IK kinds: armtwin5 (§4) and track6 (numeric, URDF chain).
 */
import { describe, expect, test } from 'vitest';
import { SimModel } from '../src/model.ts';
import { runPayload, T0 } from './run-payload.ts';
import { loadSimProfile } from '../src/profile.ts';

const run = runPayload;

describe('the floor in the simulator', () => {
  test('armtwin5: a joint move that puts the hand under the floor is $ERR:floor and moves nothing', () => {
    const m = new SimModel(loadSimProfile('armtwin5').model, T0);
    // Upper arm and forearm level: the hand at z 100, allowed.
    expect(run(m, '#001P0833T0100!', T0)).toEqual([]);
    // Forearm pointing down from there: tip at z −148.
    expect(run(m, '#002P0833T0100!', T0 + 1000)).toEqual([
      expect.stringMatching(/^\$ERR:floor: tip 148\.\d mm below the floor \(z -148\.\d < 0\)!$/),
    ]);
    expect(run(m, '{#001P0833T0100!#002P0833T0100!}', T0 + 1000)).toEqual([
      expect.stringMatching(/^\$ERR:group rejected: floor: tip 148\.\d mm below the floor/),
    ]);
    expect(m.counters.rejected.floor).toBe(2);
    expect(m.pwmAt(2, T0 + 2000)).toBe(1500);
  });

  test('armtwin5: $KMS to a reachable point under the floor is $KMS:1! and nothing moves', () => {
    const m = new SimModel(loadSimProfile('armtwin5').model, T0);
    expect(run(m, '$KMS:200,0,-50,500!', T0)).toEqual(['$KMS:1!']);
    expect(run(m, '$KMS:200,0,20,500!', T0)).toEqual(['$KMS:0!']);
    expect(m.counters.rejected.floor).toBe(1);
  });

  test('track6 (numeric): $KMS under the floor is refused, the same point above it is not', () => {
    const m = new SimModel(loadSimProfile('track6').model, T0);
    expect(run(m, '$KMS:1500,0,-200,500!', T0)).toEqual(['$KMS:1!']);
    expect(run(m, '$KMS:1500,0,200,500!', T0)).toEqual(['$KMS:0!']);
    expect(m.counters.rejected.floor).toBe(1);
  });
});
