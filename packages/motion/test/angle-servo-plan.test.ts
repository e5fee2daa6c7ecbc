/**
 * A plan for an arm with a servo that speaks angles (profile `"units": "angle"`, PROTOCOL §8):
 * that servo is streamed as `#IIIA±ddd.ddTtttt!` and reaches +350.00° whole; the pulse servos
 * beside it still get `#IIIPppppTtttt!`.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { parseProfile, pwmFromServo } from '@armtwin/robot';
import { createReader, type Frame } from '@armtwin/protocol';
import { createMotionRobot, planJoint, toMoveFrames } from '../src/index.ts';
import { home, limitProblems } from './fixtures.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');

function busRobot() {
  const raw = JSON.parse(
    fs.readFileSync(path.join(MODELS, 'armtwin5', 'profile.json'), 'utf8'),
  ) as {
    servos: Record<string, unknown>[];
  };
  raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
  const parsed = parseProfile(raw);
  if (!parsed.ok) throw new Error(parsed.errors.join('; '));
  return createMotionRobot(parsed.profile);
}

describe('plans for a servo that speaks angles', () => {
  it('stream angle moves to it, reaching +350.00° exactly, and pulse moves to the others', () => {
    const robot = busRobot();
    const from = home(robot);
    const to = [...from];
    to[4] = pwmFromServo(robot.profile.servos[4]!, 350);
    to[2] = pwmFromServo(robot.profile.servos[2]!, 30);
    const plan = planJoint(robot, from, [to], { speed: 1 });
    expect(limitProblems(robot, plan, 1)).toEqual([]);
    const frames = toMoveFrames(plan, 20, robot.table);
    const last = new Map<number, Frame>();
    const reader = createReader({
      onGroup: (g) => {
        expect(g.invalid).toBe(0);
        for (const f of g.frames) if ('id' in f) last.set(f.id, f);
      },
      onError: (e) => {
        throw new Error(e.message);
      },
    });
    for (const f of frames) reader.feed(f.frame);
    expect(last.get(4)).toMatchObject({ type: 'angleMove', id: 4, deg: 350 });
    expect(last.get(2)).toMatchObject({ type: 'move', id: 2, pwm: 1722 });
    expect(frames.every((f) => !/#004P/.test(f.frame))).toBe(true);
  });

  it('without the table every servo is streamed in pulses, as before', () => {
    const robot = busRobot();
    const to = home(robot);
    to[2] = 1600;
    const frames = toMoveFrames(planJoint(robot, home(robot), [to], { speed: 1 }), 20);
    expect(frames.at(-1)!.frame).toMatch(/#002P1600T\d{4}!/);
  });
});
