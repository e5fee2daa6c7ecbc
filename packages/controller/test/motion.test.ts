/**
 * Motion requests executed by the controller core on a driver of plain arrays, time handed in
 * as numbers: a joint request is planned, streamed as goals at each step and ends `done` at its
 * target; plan-only moves nothing; a command through the core ends an execution as `stopped`;
 * a sender the arbiter refuses moves nothing; a driver not ready refuses to execute.
 */
import fs from 'node:fs';
import { describe, expect, test } from 'vitest';
import { armProfileFromProfile, parseProfile } from '@armtwin/robot';
import { createMotionRobot } from '@armtwin/motion';
import { ControlInput, ControllerCore, jointsFromArm, MotionRequests } from '../src/index.ts';
import { ArrayDriver } from './array-driver.ts';

function rig(mayExecute?: (user: string) => string) {
  const url = new URL('../../../public/models/armtwin5/profile.json', import.meta.url);
  const parsed = parseProfile(JSON.parse(fs.readFileSync(url, 'utf8')));
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  const robot = createMotionRobot(parsed.profile);
  const driver = new ArrayDriver();
  const core = new ControllerCore(jointsFromArm(armProfileFromProfile(parsed.profile)!), driver);
  const motion = new MotionRequests(core, () => robot, 0, mayExecute ? { mayExecute } : {});
  /** Steps every `stepMs` from t until the execution ends; the feedback and the end time. */
  const runFrom = (t: number) => {
    const out = [];
    while (motion.running && t < 60_000) out.push(...motion.step((t += motion.stepMs)));
    return { out, t };
  };
  return { driver, core, motion, runFrom };
}

const joint = (id: string, execute: boolean) =>
  JSON.stringify({ id, mode: 'joint', targets: [{ servos: { '000': 1800 } }], execute });

describe('motion requests on the controller core', () => {
  test('executed: planned, started, streamed as goals, done at the target', () => {
    const r = rig();
    const first = r.motion.request(joint('j1', true), '', 0);
    expect(first.map((f) => f.status)).toEqual(['planned', 'executing']);
    const { out, t } = r.runFrom(0);
    expect(out.at(-1)).toMatchObject({ id: 'j1', status: 'done' });
    expect(r.driver.pose(t)[0]).toBeCloseTo(1800, 3);
    expect(r.driver.moves.length).toBeGreaterThan(1);
  });

  test('plan only moves nothing', () => {
    const r = rig();
    const out = r.motion.request(joint('p1', false), '', 0);
    expect(out).toEqual([
      expect.objectContaining({ status: 'planned', message: expect.stringContaining('plan only') }),
    ]);
    expect(r.motion.running).toBe(false);
    expect(r.driver.moves).toEqual([]);
  });

  test('a command through the core ends the execution as stopped', () => {
    const r = rig();
    r.motion.request(joint('s1', true), '', 0);
    r.motion.step(20);
    new ControlInput(r.core, {}, 30).receive('#255PDST!', 30);
    expect(r.motion.step(40)).toEqual([
      expect.objectContaining({
        id: 's1',
        status: 'stopped',
        message: 'stopped: emergency stop (#255PDST!)',
      }),
    ]);
    expect(r.motion.running).toBe(false);
  });

  test('refused for a sender who may not move the arm, or a driver not ready: nothing moves', () => {
    const r = rig((user) => (user === 'bob' ? 'controlled by alice' : ''));
    expect(r.motion.request(joint('b1', true), 'bob', 0)).toEqual([
      expect.objectContaining({ status: 'failed', message: 'not executed: controlled by alice' }),
    ]);
    r.driver.notReady = 'gateway: serial line down';
    expect(r.motion.request(joint('b2', true), 'alice', 0)).toEqual([
      expect.objectContaining({
        status: 'failed',
        message: 'not executed: gateway: serial line down',
      }),
    ]);
    expect(r.driver.moves).toEqual([]);
  });
});
