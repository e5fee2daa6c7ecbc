/**
 * The store keeps each servo by its place in the profile, whatever ids the arm's frames name:
 * the SO-101's Feetech ids 001–006 (as LeRobot numbers them) land in slots 0–5, the gripper
 * (006) included; an id the arm does not have is ignored. (The store once used the id as the
 * index: servo 001 was drawn as the second joint and the gripper never moved on the page.)
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, it } from 'vitest';
import { encodeAngle, encodeAngleMove, encodeGroup, encodeHealth } from '@armtwin/protocol';
import { parseProfile, servoModelArm } from '@armtwin/robot';
import { ArmStore } from '../src/core/store/ArmStore.ts';

const file = path.resolve(import.meta.dirname, '../../../public/models/so101/profile.json');
const parsed = parseProfile(JSON.parse(fs.readFileSync(file, 'utf8')));
if (!parsed.ok) throw new Error(parsed.errors.join('; '));
const SO101 = servoModelArm(parsed.profile);
const angles = (degs: number[]) => encodeGroup(degs.map((d, i) => encodeAngle(i + 1, d)));

describe('ArmStore with the SO-101 (servo ids 001–006)', () => {
  it('puts each reported servo in its profile slot, the gripper in the last', () => {
    const s = new ArmStore({ arm: SO101, twinMode: 'newest' });
    expect(SO101.servos.map((x) => x.id)).toEqual([1, 2, 3, 4, 5, 6]);
    s.ingest(`$TIM:1700000000000!${angles([10, -20, 30, -40, 50, 30])}`, 0);
    expect(Array.from(s.angle)).toEqual([10, -20, 30, -40, 50, 30]);
    s.sample(100);
    expect(Array.from(s.rendered)).toEqual([10, -20, 30, -40, 50, 30]);
    expect(s.counters.dropped).toBe(0);
  });

  it('takes health by id too, and ignores an id the arm does not have', () => {
    const s = new ArmStore({ arm: SO101 });
    s.ingest(encodeGroup([0, 1, 6].map((id) => encodeHealth(id, 40 + id, 12000 + id))), 0);
    expect(s.temp[0]).toBe(41);
    expect(s.mv[5]).toBe(12006);
    expect(Array.from(s.temp).filter(Number.isFinite)).toEqual([41, 46]);
  });

  it("follows a command to the gripper (006) in the predicted twin, not another joint's", () => {
    const s = new ArmStore({ arm: SO101, twinMode: 'predict' });
    s.ingest(`$TIM:1700000000000!${angles([0, 0, 0, 0, 0, 0])}`, 0);
    s.noteControl(encodeAngleMove(6, 30, 1000), 10);
    s.sample(510);
    expect(s.rendered[5]).toBeGreaterThan(0);
    expect(Array.from(s.rendered.slice(0, 5))).toEqual([0, 0, 0, 0, 0]);
  });

  it("keeps this page's command to the gripper (006) in the gripper's slot, where the ghost reads it", () => {
    const s = new ArmStore({ arm: SO101 });
    s.setCommanded(6, 1700);
    s.setCommanded(0, 1600); // the SO-101 has no servo 000
    expect(Array.from(s.commandedPwm).map((v) => (Number.isNaN(v) ? null : v))).toEqual([
      null,
      null,
      null,
      null,
      null,
      1700,
    ]);
    s.setCommanded(6, NaN);
    expect(s.commandedPwm.every(Number.isNaN)).toBe(true);
  });
});
