/** Shared by the motion tests: the shipped robots as the planner sees them, and checks on plans. */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chainFromUrdf, parseProfile } from '@armtwin/robot';
import { createMotionRobot, topSpeed, type MotionRobot, type Plan } from '../src/index.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');

export function loadRobot(name: string): MotionRobot {
  const read = (f: string) => fs.readFileSync(path.join(MODELS, name, f), 'utf8');
  const parsed = parseProfile(JSON.parse(read('profile.json')));
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  const built = chainFromUrdf(parsed.profile, read(parsed.profile.urdf));
  if (!built.ok) throw new Error(built.errors.join('\n'));
  return createMotionRobot(
    parsed.profile,
    parsed.profile.ik.kind === 'numeric' ? built.chain : undefined,
  );
}

export const home = (r: MotionRobot) => r.table.map((s) => s.homePwm);

/** Every problem with a plan's limits: pulses outside a servo's range, speeds above its limit, time not increasing. */
export function limitProblems(robot: MotionRobot, plan: Plan, speed: number): string[] {
  const out: string[] = [];
  plan.samples.forEach((s, k) => {
    s.pwm.forEach((p, i) => {
      const { minPwm, maxPwm } = robot.table[i]!;
      if (!(p >= minPwm && p <= maxPwm))
        out.push(`sample ${k} servo ${i}: ${p} outside ${minPwm}–${maxPwm}`);
    });
    if (k === 0) return;
    const prev = plan.samples[k - 1]!;
    const dt = s.t - prev.t;
    if (!(dt > 0)) out.push(`sample ${k}: time ${s.t} after ${prev.t}`);
    s.pwm.forEach((p, i) => {
      const v = Math.abs(p - prev.pwm[i]!) / dt;
      const max = topSpeed(robot, i, speed);
      if (v > max * (1 + 1e-9) + 1e-9) out.push(`sample ${k} servo ${i}: ${v} µs/ms > ${max}`);
    });
  });
  return out;
}
