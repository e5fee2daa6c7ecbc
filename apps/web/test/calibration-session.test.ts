/**
 * The calibration wizard's plain state on a real store: its jogs are slow angle moves from the
 * last target, refused beyond the limits in force; an emergency stop makes the next jog start
 * from where the arm is; the ghost shows the joint at zero, leaning positive, then where the new
 * calibration reads it; the recorded readings give the result.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect, test, vi } from 'vitest';
import { parseProfile, type Profile } from '@armtwin/robot';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { robotSpec } from '../src/core/robots/robotSpec.ts';
import { CalibrationSession } from '../src/core/calibration/CalibrationSession.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');

/** armtwin5 with its elbow (002) a bus servo, polarity −1, offset +20, limits ±150. */
function busProfile(): Profile {
  const raw = JSON.parse(fs.readFileSync(path.join(MODELS, 'armtwin5', 'profile.json'), 'utf8'));
  raw.servos[2] = {
    ...raw.servos[2],
    units: 'angle',
    polarity: -1,
    offset: 20,
    min: -150,
    max: 150,
  };
  const r = parseProfile(raw);
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.profile;
}

function rig() {
  const profile = busProfile();
  const store = new ArmStore({ arm: robotSpec(profile).storeArm });
  let t = 0;
  const report = (elbow: number) =>
    store.ingest(
      `{#000P1500!#001P1500!#002A${elbow < 0 ? '-' : '+'}${Math.abs(elbow).toFixed(2).padStart(6, '0')}!#003P1500!#004P1500!#005P1500!}`,
      (t += 20),
    );
  const sent: string[] = [];
  const link = { sendGroup: (f: string) => (sent.push(f), true) };
  const wizard = new CalibrationSession(store);
  wizard.begin(profile, 2);
  return { store, report, sent, link, wizard };
}

test('jogs are slow angle moves from the last target, within the limits in force', () => {
  const { report, sent, link, wizard } = rig();
  expect(wizard.jog(link, 1)).toMatch(/no reading/);
  report(0);
  expect(wizard.jog(link, -10)).toBe('');
  expect(wizard.jog(link, -5)).toBe('');
  // 15° at 15°/s from where it is: 1 s
  expect(sent).toEqual(['{#002A-010.00T0667!}', '{#002A-015.00T1000!}']);
  // the limits in force are −170…130° of servo angle (−150…150 less the offset 20)
  expect(wizard.jog(link, -160)).toMatch(/outside the limits in force/);
  expect(sent).toHaveLength(2);
  // after a stop the next jog starts from where the arm is
  report(-12);
  wizard.stopped();
  expect(wizard.jog(link, 1)).toBe('');
  expect(sent.at(-1)).toBe('{#002A-011.00T0200!}');
  expect(wizard.jog({ sendGroup: () => false }, 1)).toMatch(/not sent/);
});

test('the ghost shows zero, then the lean, then the joint as the new calibration reads it', () => {
  vi.useFakeTimers();
  const { report, wizard } = rig();
  const ghost = new Float64Array(6);
  report(0);
  wizard.setOpen(true);
  // servo angles in the terms in force (joint − offset 20)
  expect(wizard.sample(0, ghost)).toBe(true);
  expect(ghost[2]).toBe(-20);
  report(-15);
  expect(wizard.record()).toBe(true);
  expect(wizard.step).toBe('direction');
  wizard.sample(0, ghost);
  expect(ghost[2]).toBe(10);
  report(-45);
  wizard.record();
  expect(wizard.step).toBe('range');
  report(-105);
  vi.advanceTimersByTime(50); // the travel is sampled while it is recorded
  wizard.sample(0, ghost);
  expect(ghost[2]! + 20).toBeCloseTo(90, 9); // the real joint: −(r + 15)
  report(15);
  wizard.record();
  expect(wizard.step).toBe('review');
  expect(wizard.result()).toEqual({
    ok: true,
    fields: { id: 2, polarity: 1, offset: -15, min: -30, max: 90 },
  });
  wizard.markSaved();
  expect(wizard.sample(0, ghost)).toBe(false);
  wizard.setOpen(false);
  vi.useRealTimers();
});
