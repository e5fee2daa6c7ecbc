/**
 * The fleet list's state (src/core/robots/fleet.ts), the retained profile announcement, motion
 * feedback as untrusted input, the arm switch's URL, and the HUD's pose-checking thresholds.
 */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';
import { parseProfile } from '@armtwin/robot';
import type { ArmSummary } from '@armtwin/protocol';
import { createMotionRobot, planRequest, DEFAULT_EXECUTE_OPTIONS } from '@armtwin/motion';
import {
  EMPTY_FLEET,
  fleetList,
  reduceFleet,
  sameSummary,
  type FleetState,
} from '../src/core/robots/fleet.ts';
import { feedbackWords, parseFeedback } from '../src/core/robots/feedback.ts';
import { queryWithArm } from '../src/core/robots/selectArm.ts';
import { hudExecuteOptions, planPeakSpeeds } from '../src/core/plan/executeOptions.ts';

const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');
const profileText = (name: string) =>
  fs.readFileSync(path.join(MODELS, name, 'profile.json'), 'utf8');

describe('reduceFleet', () => {
  const online = (id: string, text: string) => ({ kind: 'online' as const, id, text });

  it('adds arms as they appear, follows online / offline; online first, then by id (arm2 before arm10)', () => {
    let s: FleetState = EMPTY_FLEET;
    s = reduceFleet(s, online('arm2', '1'));
    s = reduceFleet(s, online('arm1', '0'));
    s = reduceFleet(s, { kind: 'profile', id: 'arm2', name: 'track6', title: 'Track arm' });
    s = reduceFleet(s, online('arm0', '0'));
    s = reduceFleet(s, online('arm10', '1'));
    expect(fleetList(s).map((a) => [a.id, a.online, a.profileName, a.level])).toEqual([
      ['arm2', true, 'track6', 'unknown'],
      ['arm10', true, null, 'unknown'],
      ['arm0', false, null, 'unknown'],
      ['arm1', false, null, 'unknown'],
    ]);
    s = reduceFleet(s, online('arm1', '1'));
    expect(s.get('arm1')!.online).toBe(true);
    expect(reduceFleet(s, online('arm1', 'junk')).get('arm1')!.online).toBeNull();
  });

  it('returns the same state when nothing changes, and ignores bad arm ids', () => {
    const s = reduceFleet(EMPTY_FLEET, online('arm1', '1'));
    expect(reduceFleet(s, online('arm1', '1'))).toBe(s);
    expect(reduceFleet(s, online('Not/An/Id', '1'))).toBe(s);
    expect(reduceFleet(s, online('x'.repeat(33), '1'))).toBe(s);
  });

  it('the summary: the worst health in words, state, holder and pose; a cleared one forgets them', () => {
    let s = reduceFleet(EMPTY_FLEET, online('arm1', '1'));
    const summary = (o: Partial<ArmSummary>) =>
      (s = reduceFleet(s, {
        kind: 'summary',
        id: 'arm1',
        summary: {
          t: 1,
          state: 'still',
          why: '',
          health: 'normal',
          alarm: '',
          holder: null,
          joints: [{ id: 0, deg: 0, min: -90, max: 90 }],
          error: null,
          ...o,
        },
      }));
    summary({});
    expect([s.get('arm1')!.level, s.get('arm1')!.alarm]).toEqual(['normal', '']);
    const before = s.get('arm1');
    summary({ health: 'warning', alarm: 'servo 001: 65 °C' });
    expect(s.get('arm1')!.level).toBe('warning');
    expect(s.get('arm1')!.alarm).toBe('servo 001: 65 °C');
    expect(sameSummary(before, s.get('arm1'))).toBe(false);
    summary({ health: 'warning', alarm: 'servo 001: 65 °C', holder: 'bob', state: 'moving' });
    expect(s.get('arm1')).toMatchObject({ holder: 'bob', state: 'moving' });
    const again = s.get('arm1');
    summary({ health: 'warning', alarm: 'servo 001: 65 °C', holder: 'bob', state: 'moving', t: 2 });
    expect(sameSummary(again, s.get('arm1'))).toBe(true); // a newer summary, the row the same
    summary({
      health: 'warning',
      alarm: 'servo 001: 65 °C',
      holder: 'bob',
      state: 'moving',
      joints: [{ id: 0, deg: 5, min: -90, max: 90 }],
    });
    expect(sameSummary(again, s.get('arm1'))).toBe(false); // the pose moved
    s = reduceFleet(s, { kind: 'summary', id: 'arm1', summary: null });
    expect(s.get('arm1')).toMatchObject({
      level: 'unknown',
      state: null,
      holder: null,
      joints: [],
    });
  });

  it('early warnings: raised per servo, cleared per servo', () => {
    const alert = (kind: 'thermal-warning' | 'thermal-cleared', id: string) => ({
      kind: 'alert' as const,
      id: 'arm1',
      alert: {
        at: 1,
        kind,
        id,
        tempC: 50,
        predictedC: 40,
        excessCPerS: 1,
        secondsToLimit: 10,
        detail: `servo ${id} heats`,
      },
    });
    let s = reduceFleet(EMPTY_FLEET, alert('thermal-warning', '002'));
    s = reduceFleet(s, alert('thermal-warning', '003'));
    expect(s.get('arm1')!.warnings).toEqual({ '002': 'servo 002 heats', '003': 'servo 003 heats' });
    s = reduceFleet(s, alert('thermal-cleared', '002'));
    expect(s.get('arm1')!.warnings).toEqual({ '003': 'servo 003 heats' });
    expect(reduceFleet(s, alert('thermal-cleared', '002'))).toBe(s);
  });
});

describe('motion feedback', () => {
  it('reads the fields the HUD shows and words them', () => {
    const f = parseFeedback('{"id":"r1","status":"unreachable","code":2,"message":"x","target":0}');
    expect(f).toEqual({ id: 'r1', status: 'unreachable', code: 2, message: 'x' });
    expect(feedbackWords(f!)).toBe('unreachable: out of reach (code 2)');
    expect(feedbackWords(parseFeedback('{"id":"r","status":"done","code":0,"message":""}')!)).toBe(
      'done',
    );
    expect(
      feedbackWords(
        parseFeedback('{"id":"r","status":"failed","code":20,"message":"targets[0].x: bad"}')!,
      ),
    ).toBe('failed (code 20): targets[0].x: bad');
    const paused = parseFeedback(
      '{"id":"r","status":"executing","code":0,"message":"","event":"paused","servo":"001","deviation":7.25}',
    );
    expect(feedbackWords(paused!)).toBe('paused: servo 001 off the plan by 7.3, re-planning');
  });

  it('refuses anything else; long text is cut', () => {
    for (const t of ['', 'nope', '[]', 'null', '{"status":"exploded"}', '{"id":1}'])
      expect(parseFeedback(t), t).toBeNull();
    const long = parseFeedback(
      JSON.stringify({ id: 'r', status: 'failed', code: 20, message: 'm'.repeat(5000) }),
    );
    expect(long!.message.length).toBe(300);
    expect(parseFeedback(JSON.stringify({ status: 'done', id: 5, code: 'x' }))).toEqual({
      id: null,
      status: 'done',
      code: 0,
      message: '',
    });
  });
});

describe('selecting an arm', () => {
  it('sets arm= in the query and keeps the rest', () => {
    expect(queryWithArm('?broker=ws%3A%2F%2Fh%3A1&arm=arm1', 'arm2')).toBe(
      '?broker=ws%3A%2F%2Fh%3A1&arm=arm2',
    );
    expect(queryWithArm('', 'arm7')).toBe('?arm=arm7');
  });
});

describe('HUD pose-checking thresholds', () => {
  const p = parseProfile(JSON.parse(profileText('armtwin5')));
  if (!p.ok) throw new Error('armtwin5');
  const robot = createMotionRobot(p.profile);
  const home = [1500, 1500, 1500, 1500, 1500, 1500];
  const plan = (speed: number) => {
    const o = planRequest(robot, { id: 'a', mode: 'joint', targets: ['ready'], speed }, home);
    if (o.status !== 'planned') throw new Error(o.message);
    return o.plan;
  };

  it("the arm's threshold plus what the view's lag explains at the plan's peak speed", () => {
    const slow = plan(0.1);
    const fast = plan(0.5);
    expect(planPeakSpeeds(robot, fast).deg).toBeGreaterThan(planPeakSpeeds(robot, slow).deg * 3);
    const o = hudExecuteOptions(robot, slow, 20);
    const peak = planPeakSpeeds(robot, slow).deg;
    expect(o.thresholdDeg).toBeCloseTo(DEFAULT_EXECUTE_OPTIONS.thresholdDeg + peak * 0.18, 9);
    expect(o.stepMs).toBe(100);
    expect(hudExecuteOptions(robot, fast, 20).thresholdDeg!).toBeGreaterThan(o.thresholdDeg!);
    expect(o.thresholdMm).toBe(DEFAULT_EXECUTE_OPTIONS.thresholdMm); // no prismatic axis
  });
});
