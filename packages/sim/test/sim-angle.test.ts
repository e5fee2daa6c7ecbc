/**
 * Angle frames (PROTOCOL §8) in the simulator: `#IIIA…T…!` moves checked in degrees against the
 * profile, and position reports in angle frames as the profile says or as asked (`--report`).
 */
import fs from 'node:fs';
import path from 'node:path';
import { describe, expect, test } from 'vitest';
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';
import { parseProfile } from '@armtwin/robot';
import fc from 'fast-check';
import { createReader, encodeAngle, type Frame, type Group } from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { SimModel } from '../src/model.ts';
import { MODELS_DIR, simProfile } from '../src/profile.ts';
import { SimRunner, type PayloadKind } from '../src/runner.ts';
import { StatusWriter } from '../src/status-writer.ts';

const T0 = 1_000_000;
/** The demo arm with a bus servo as wrist roll (004): ±360° of travel, speaking angles. */
const BUS_ARM: ArmProfile = {
  ...DEMO_ARM,
  servos: DEMO_ARM.servos.map((s) =>
    s.id === 4 ? { ...s, minDeg: -360, maxDeg: 360, units: 'angle' as const } : s,
  ),
};
const angleMove = (id: number, deg: number, ms: number): Frame => ({
  type: 'angleMove',
  id,
  deg,
  ms,
});

function run(model: SimModel, frame: Frame, t = T0): string[] {
  const out: string[] = [];
  model.execute(frame, t, out);
  return out;
}

describe('SimModel angle moves', () => {
  test('a ±360° servo goes to +350.00° and reports exactly #004A+350.00!', () => {
    const m = new SimModel({ arm: BUS_ARM }, T0);
    expect(run(m, angleMove(4, 350, 1000))).toEqual([]);
    expect(m.angleAt(4, T0 + 500)).toBeCloseTo(175, 9);
    expect(run(m, { type: 'readPosition', id: 4 }, T0 + 2000)).toEqual(['#004A+350.00!']);
    // the pulse servos beside it still answer in pulse widths
    expect(run(m, { type: 'readPosition', id: 0 }, T0 + 2000)).toEqual(['#000P1500!']);
  });

  test('limits are checked in degrees against the profile; a refused move is $ERR and moves nothing', () => {
    const m = new SimModel({ arm: BUS_ARM }, T0);
    expect(run(m, angleMove(4, 360.01, 100))).toEqual([
      '$ERR:limit 004 A360.01 outside -360..360!',
    ]);
    expect(run(m, angleMove(1, 90.5, 100))).toEqual(['$ERR:limit 001 A90.5 outside -90..90!']);
    expect(run(m, angleMove(9, 0, 100))).toEqual(['$ERR:no servo 009!']);
    // #255 moves every servo, so every servo must allow the angle
    expect(run(m, angleMove(255, 100, 100))).toEqual(['$ERR:limit 001 A100 outside -90..90!']);
    expect(m.counters.rejected.limit).toBe(3);
    expect(run(m, { type: 'readPosition', id: 255 }, T0 + 1000)).toEqual([
      '{#000P1500!#001P1500!#002P1500!#003P1500!#004A+000.00!#005P1500!}',
    ]);
  });

  test('a pulse servo takes angle moves too, and #255A… moves every servo', () => {
    const m = new SimModel({}, T0);
    expect(run(m, angleMove(255, 45, 0))).toEqual([]);
    for (let i = 0; i < 6; i++) expect(m.angleAt(i, T0 + 1000)).toBeCloseTo(45, 9);
    expect(m.pwmAt(2, T0 + 1000)).toBe(1833);
  });

  test('an angle move inside a group is all or nothing, like pulse moves', () => {
    const m = new SimModel({ arm: BUS_ARM }, T0);
    const out: string[] = [];
    const bad: Group = {
      type: 'group',
      invalid: 0,
      frames: [angleMove(4, -300, 0), angleMove(3, 91, 0)],
    };
    m.executeGroup(bad, T0, out);
    expect(out).toEqual(['$ERR:group rejected: limit 003 A91 outside -90..90!']);
    expect(m.angleAt(4, T0 + 5000)).toBe(0);
    m.executeGroup(
      { ...bad, frames: [angleMove(4, -300, 0), { type: 'move', id: 3, pwm: 1600, ms: 0 }] },
      T0,
      out,
    );
    expect(m.angleAt(4, T0 + 5000)).toBeCloseTo(-300, 9);
    expect(m.pwmAt(3, T0 + 5000)).toBe(1600);
  });

  test('report "angle" reports every servo in angle frames; "pulse" every servo in pulse widths', () => {
    const a = new SimModel({ report: 'angle' }, T0);
    run(a, { type: 'move', id: 1, pwm: 1600, ms: 0 });
    expect(run(a, { type: 'readPosition', id: 1 }, T0 + 1000)).toEqual(['#001A+013.50!']);
    const p = new SimModel({ arm: BUS_ARM, report: 'pulse' }, T0);
    expect(run(p, { type: 'readPosition', id: 4 })).toEqual(['#004P1500!']);
    run(p, angleMove(4, 350, 0));
    // beyond the pulse range: held at its end rather than written as an invalid frame
    expect(run(p, { type: 'readPosition', id: 4 }, T0 + 5000)).toEqual(['#004P2500!']);
  });
});

describe('StatusWriter angle frames', () => {
  test('write what encodeAngle writes, for any angle in range', () => {
    const w = new StatusWriter(4);
    for (const deg of [0, -0, -0.004, 0.005, -12.5, 350, -359.99, 999.99, -999.99, 12.345])
      expect(w.reset().angle(4, deg).take().toString()).toBe(encodeAngle(4, deg));
    fc.assert(
      fc.property(
        fc.integer({ min: 0, max: 254 }),
        fc.double({ min: -999.99, max: 999.99, noNaN: true }),
        (id, deg) => {
          expect(w.reset().angle(id, deg).take().toString()).toBe(encodeAngle(id, deg));
        },
      ),
      { numRuns: 500 },
    );
  });
});

describe('SimRunner state stream with angle reports', () => {
  test('streams stamped groups of angle frames, and a move arrives at its angle', () => {
    const clock = new FakeClock();
    const sent: { text: string; kind: PayloadKind }[] = [];
    const runner = new SimRunner(
      { send: (p, kind) => sent.push({ text: p.toString('latin1'), kind }) },
      clock,
      {
        rate: 50,
        model: { arm: BUS_ARM, report: 'angle' },
      },
    );
    runner.start();
    runner.receive('#004A-350.00T0200!#001A+045.00T0200!');
    clock.advance(1000);
    runner.stop();
    const groups: Group[] = [];
    const reader = createReader({ onGroup: (g) => groups.push(g) });
    for (const s of sent.filter((x) => x.kind === 'state')) reader.feed(s.text);
    expect(groups.length).toBeGreaterThan(40);
    expect(
      groups.every((g) => g.time !== undefined && g.frames.every((f) => f.type === 'angle')),
    ).toBe(true);
    expect(groups.at(-1)!.frames.map((f) => (f.type === 'angle' ? f.deg : NaN))).toEqual([
      0, 45, 0, 0, -350, 0,
    ]);
  });
});

describe('a profile whose servo speaks angles', () => {
  test('armtwin5 with a ±360° wrist roll in angle units runs in the sim and reports angles', () => {
    const raw = JSON.parse(
      fs.readFileSync(path.join(MODELS_DIR, 'armtwin5', 'profile.json'), 'utf8'),
    ) as {
      servos: Record<string, unknown>[];
    };
    raw.servos[4] = { ...raw.servos[4], units: 'angle', min: -360, max: 360 };
    const parsed = parseProfile(raw);
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const sim = simProfile(parsed.profile, raw);
    const m = new SimModel(sim.model, T0);
    expect(run(m, angleMove(4, 350, 1000))).toEqual([]);
    expect(run(m, { type: 'readPosition', id: 255 }, T0 + 2000)).toEqual([
      '{#000P1500!#001P1500!#002P1500!#003P1500!#004A+350.00!#005P1500!}',
    ]);
  });
});
