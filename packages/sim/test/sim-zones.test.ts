/**
 * Keep-out zones at the controller (docs/protocol.md, "Keep-out zones"): the simulator refuses a
 * move, a group or a `$KMS` whose straight path takes a link into a zone of the profile (or onto
 * another link), with `$ERR:zone …` (or `$KMS:25!`), counts it and moves nothing; a move clear at
 * both ends but through a zone between them is refused too.
 */
import fs from 'node:fs';
import { describe, expect, test } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import { exactPwmFromServo } from '@armtwin/motion';
import { SimModel } from '../src/model.ts';
import { runPayload, T0 } from './run-payload.ts';
import { simProfile } from '../src/profile.ts';

const run = runPayload;

/** armtwin5 as shipped, plus these zones. */
function model(zones: unknown[]): SimModel {
  const url = new URL('../../../public/models/armtwin5/profile.json', import.meta.url);
  const raw = { ...JSON.parse(fs.readFileSync(url, 'utf8')), keepOut: { zones } };
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  return new SimModel(simProfile(parsed.profile, raw).model, T0);
}

/** `{#000P…T…!…}` for servo angles (deg) of servos 000–003 of armtwin5. */
const group = (deg: number[], ms = 500) =>
  `{${deg.map((d, i) => `#00${i}P${String(Math.round(exactPwmFromServo(SERVO, d))).padStart(4, '0')}T${ms}!`).join('')}}`;
const SERVO = { type: 'revolute', polarity: 1, offset: 0, units: 'pulse' } as never;

const TABLE = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };

describe('keep-out zones in the simulator', () => {
  test('a group that puts the hand into the table is $ERR:zone, counted, and moves nothing', () => {
    const m = model([TABLE]);
    expect(run(m, group([0, -45, -45, -90]), T0)).toEqual([
      expect.stringMatching(/^\$ERR:group rejected: zone: hand in "table"( on the way)?!$/),
    ]);
    expect(m.counters.rejected.zone).toBe(1);
    expect(m.counters.rejected.floor).toBe(0);
    expect([0, 1, 2, 3].map((i) => m.pwmAt(i, T0 + 2000))).toEqual([1500, 1500, 1500, 1500]);
    // The same arm without the zone takes it.
    expect(run(model([]), group([0, -45, -45, -90]), T0)).toEqual([]);
  });

  test('a base turn clear at both ends but through a wall between them is refused on the way', () => {
    const m = model([{ name: 'wall', shape: 'box', min: [100, -10, 0], max: [400, 10, 300] }]);
    expect(run(m, group([-90, -30, -60, -60]), T0)).toEqual([]);
    const at = T0 + 5000;
    const turn = `#000P${Math.round(exactPwmFromServo(SERVO, 90))}T1000!`;
    expect(run(m, turn, at)).toEqual([
      expect.stringMatching(/^\$ERR:zone: (upper arm|forearm|hand) in "wall" on the way!$/),
    ]);
    expect(m.pwmAt(0, at + 2000)).toBe(Math.round(exactPwmFromServo(SERVO, -90)));
  });

  test('$KMS through the table is $KMS:25! and nothing moves; above it, $KMS:0!', () => {
    const m = model([TABLE]);
    expect(run(m, '$KMS:250,0,10,500!', T0)).toEqual(['$KMS:25!']);
    expect(m.counters.rejected.zone).toBe(1);
    expect(run(m, '$KMS:250,0,120,500!', T0)).toEqual(['$KMS:0!']);
  });
});
