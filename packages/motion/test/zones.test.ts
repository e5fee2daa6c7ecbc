/**
 * Keep-out zones and self-collision (docs/protocol.md, "Keep-out zones"): the profile's
 * `keepOut` validated with messages naming the zone and field; poses, moves (their straight
 * joint-space path) and plans refused when a link enters a zone (25) or touches another (26);
 * an arm already inside allowed out; the geometry against brute force.
 */
import fs from 'node:fs';
import fc from 'fast-check';
import { describe, expect, test } from 'vitest';
import { parseProfile, type ProfileKeepOut, type Zone } from '@armtwin/robot';
import {
  CODE_IN_ZONE,
  CODE_SELF_COLLISION,
  armLinks,
  checkZones,
  checkZonesMove,
  createMotionRobot,
  exactPwmFromServo,
  keepOutReason,
  planInZone,
  planRequest,
  segmentZoneDistance,
  zoneDistance,
  type MotionRobot,
} from '../src/index.ts';
import { home, loadRobot } from './fixtures.ts';

/** A table in front of armtwin5: top at z 30, from x 150 to 400. */
const TABLE: Zone = { name: 'table', shape: 'box', min: [150, -150, -20], max: [400, 150, 30] };

function armtwin5With(keepOut: unknown): MotionRobot {
  const parsed = parseProfile({ ...rawProfile(), keepOut });
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  return createMotionRobot(parsed.profile);
}

/** armtwin5 pulses for servo angles (deg) of servos 000–003; the rest at home. */
const pose = (robot: MotionRobot, deg: number[]) =>
  robot.profile.servos.map((s, i) => exactPwmFromServo(s, deg[i] ?? 0));

describe('keepOut in the profile', () => {
  test('boxes, cylinders and planes parse; a plane normal is made unit length', () => {
    const parsed = parseProfile({
      ...rawProfile(),
      keepOut: {
        linkRadius: 15,
        zones: [
          TABLE,
          { name: 'post', shape: 'cylinder', center: [0, 200], radius: 30, zMin: 0, zMax: 500 },
          { name: 'operator side', shape: 'plane', point: [0, -250, 0], normal: [0, -2, 0] },
        ],
      },
    });
    expect(parsed.ok).toBe(true);
    if (!parsed.ok) return;
    expect(parsed.profile.keepOut?.linkRadius).toBe(15);
    expect(parsed.profile.keepOut?.zones.map((z) => z.name)).toEqual([
      'table',
      'post',
      'operator side',
    ]);
    expect(parsed.profile.keepOut?.zones[2]).toMatchObject({ normal: [0, -1, 0] });
  });

  test('a zone file with nonsense in it is refused whole, each message naming zone and field', () => {
    const parsed = parseProfile({
      ...rawProfile(),
      keepOut: {
        linkRadius: -3,
        zones: [
          { name: 'table', shape: 'box', min: [0, 0, 0], max: [100, 'high', -5] },
          { name: 'post', shape: 'cone', radius: 3 },
          { name: 'wall', shape: 'plane', point: [0, 0, 0], normal: [0, 0, 0] },
          { name: 'tube', shape: 'cylinder', center: [0, 0], radius: 5, zMin: 9, zMax: 1, h: 2 },
          'table',
        ],
      },
    });
    expect(parsed.ok).toBe(false);
    if (parsed.ok) return;
    expect(parsed.errors).toEqual([
      expect.stringMatching(/^keepOut\.linkRadius: must be greater than 0/),
      expect.stringMatching(/^keepOut\.zones\[0\] "table"\.max\[1\]: must be a finite number/),
      expect.stringMatching(
        /^keepOut\.zones\[1\] "post"\.shape: must be one of "box", "cylinder", "plane"/,
      ),
      expect.stringMatching(/^keepOut\.zones\[2\] "wall"\.normal: must not be \[0, 0, 0\]/),
      expect.stringMatching(/^keepOut\.zones\[3\] "tube"\.h: unknown field/),
      expect.stringMatching(/^keepOut\.zones\[3\] "tube"\.zMax: must be above zMin \(9\), got 1/),
      expect.stringMatching(/^keepOut\.zones\[4\]: must be an object/),
    ]);
  });

  test('the shipped arms are clear of themselves at every named pose', () => {
    for (const name of ['armtwin5', 'track6']) {
      const robot = loadRobot(name);
      for (const [pose, values] of Object.entries(robot.profile.poses)) {
        const pwm = robot.profile.servos.map((s, i) =>
          Number.isNaN(values[i]) ? robot.table[i]!.homePwm : exactPwmFromServo(s, values[i]!),
        );
        expect(checkZones(robot, pwm), `${name} ${pose}`).toEqual({ ok: true });
      }
    }
  });
});

describe('poses and plans', () => {
  const robot = armtwin5With({ zones: [TABLE] });

  test('a tip target through the table is refused (25) in both modes, one above it planned', () => {
    for (const mode of ['joint', 'cartesian'] as const) {
      const through = planRequest(
        robot,
        { id: 't', mode, targets: [{ x: 250, y: 0, z: 10 }] },
        home(robot),
      );
      expect(through).toMatchObject({ status: 'unreachable', code: CODE_IN_ZONE, target: 0 });
      expect(through.message).toMatch(
        /^targets\[0\]: (on the way: )?(hand|forearm) [\d.]+ mm into zone "table"$/,
      );
      const above = planRequest(
        robot,
        { id: 'a', mode, targets: [{ x: 250, y: 0, z: 120 }] },
        home(robot),
      );
      expect(above).toMatchObject({ status: 'planned', code: 0 });
    }
  });

  test('a move clear at both ends but through a wall between them is refused on the way', () => {
    const wall: Zone = { name: 'wall', shape: 'box', min: [100, -10, 0], max: [400, 10, 300] };
    const r = armtwin5With({ zones: [wall] });
    const left = pose(r, [-90, -30, -60, -60]);
    const right = pose(r, [90, -30, -60, -60]);
    expect(checkZones(r, left)).toEqual({ ok: true });
    expect(checkZones(r, right)).toEqual({ ok: true });
    const c = checkZonesMove(r, left, right);
    expect(c).toMatchObject({ ok: false, kind: 'zone', other: 'wall' });
    if (c.ok) return;
    expect(c.at).toBeGreaterThan(0.3);
    expect(c.at).toBeLessThan(0.7);
    expect(c.message).toMatch(/^on the way: \w+( \w+)? [\d.]+ mm into zone "wall"$/);
    // A two-sample plan (as a controller would run it) is refused between its samples too.
    const plan = {
      samples: [
        { t: 0, pwm: left },
        { t: 1000, pwm: right },
      ],
      targetTimes: [1000],
      durationMs: 1000,
      mode: 'joint' as const,
    };
    expect(planInZone(r, plan as never)).toMatchObject({ sample: 1, check: { other: 'wall' } });
    expect(keepOutReason(r, left, right)).toMatch(
      /^zone: (upper arm|forearm|hand) in "wall" on the way$/,
    );
  });

  test('self-collision: the hand folded back into the base is refused (26)', () => {
    const folded = pose(robot, [0, 0, -135, -90]);
    expect(checkZones(robot, folded)).toMatchObject({ ok: false, kind: 'self', link: 'hand' });
    const bare = armtwin5With({ zones: [] });
    const r = planRequest(
      bare,
      { id: 's', mode: 'joint', targets: [{ unit: 'servo', servos: { '002': -135, '003': -90 } }] },
      home(bare),
    );
    expect(r).toMatchObject({ status: 'unreachable', code: CODE_SELF_COLLISION });
    expect(r.message).toMatch(/the base \(self-collision\)$/);
    const off = armtwin5With({ selfCollision: false, zones: [] });
    expect(checkZones(off, folded)).toEqual({ ok: true });
  });

  test('an arm already in a zone may come out, never go deeper', () => {
    const inside = pose(robot, [0, -45, -45, -90]); // hand down into the table, tip at z 24
    const c = checkZones(robot, inside);
    expect(c).toMatchObject({ ok: false, other: 'table' });
    expect(checkZonesMove(robot, inside, home(robot))).toEqual({ ok: true });
    expect(checkZonesMove(robot, inside, pose(robot, [0, -45, -50, -90]))).toMatchObject({
      ok: false,
      other: 'table',
    });
    const out = planRequest(robot, { id: 'u', mode: 'joint', targets: ['home'] }, inside);
    expect(out).toMatchObject({ status: 'planned' });
  });

  test('floor first, then zones: keepOutReason names the kind', () => {
    expect(keepOutReason(robot, home(robot), pose(robot, [0, -90, -90, 0]))).toMatch(/^floor: /);
    expect(keepOutReason(robot, home(robot), pose(robot, [0, -45, -45, -90]))).toMatch(/^zone: /);
    expect(keepOutReason(robot, home(robot), pose(robot, [0, -30, -60, -60]))).toBe('');
  });
});

describe('properties', () => {
  const base = loadRobot('armtwin5');
  const angles = fc.tuple(
    fc.double({ min: -135, max: 135, noNaN: true }),
    fc.double({ min: -90, max: 90, noNaN: true }),
    fc.double({ min: -135, max: 135, noNaN: true }),
    fc.double({ min: -90, max: 90, noNaN: true }),
  );

  test('a box around any point of a moving link always refuses the pose', () => {
    fc.assert(
      fc.property(
        angles,
        fc.integer({ min: 1, max: 3 }),
        fc.double({ min: 0, max: 1, noNaN: true }),
        (a, link, f) => {
          const pwm = pose(base, a);
          const p = armLinks(base, pwm)!.points;
          const at = (k: number) =>
            p[3 * link + k]! + f * (p[3 * link + 3 + k]! - p[3 * link + k]!);
          const [x, y, z] = [at(0), at(1), at(2)];
          const box: Zone = {
            name: 'b',
            shape: 'box',
            min: [x - 1, y - 1, z - 1],
            max: [x + 1, y + 1, z + 1],
          };
          const c = checkZones(base, pwm, { zones: [box], selfCollision: false });
          return !c.ok && c.kind === 'zone' && c.depth >= 20;
        },
      ),
    );
  });

  test('a zone beyond the arm’s reach never refuses anything', () => {
    const far: ProfileKeepOut = {
      zones: [
        { name: 'far box', shape: 'box', min: [600, -50, 0], max: [700, 50, 100] },
        { name: 'far post', shape: 'cylinder', center: [-600, 0], radius: 50, zMin: 0, zMax: 900 },
        { name: 'sky', shape: 'plane', point: [0, 0, 500], normal: [0, 0, 1] },
      ],
      selfCollision: false,
    };
    fc.assert(fc.property(angles, (a) => checkZones(base, pose(base, a), far).ok));
  });

  test('the least distance along a segment matches brute force within 0.5 mm', () => {
    const v = fc.double({ min: -300, max: 300, noNaN: true });
    const zones: Zone[] = [
      TABLE,
      { name: 'c', shape: 'cylinder', center: [50, -20], radius: 40, zMin: 0, zMax: 120 },
      { name: 'p', shape: 'plane', point: [0, 0, 50], normal: [0.6, 0, 0.8] },
    ];
    fc.assert(
      fc.property(
        fc.array(v, { minLength: 6, maxLength: 6 }),
        fc.integer({ min: 0, max: 2 }),
        (xs, k) => {
          const p = Float64Array.from(xs);
          const zone = zones[k]!;
          let brute = Infinity;
          for (let i = 0; i <= 2000; i++) {
            const t = i / 2000;
            brute = Math.min(
              brute,
              zoneDistance(
                zone,
                p[0]! + t * (p[3]! - p[0]!),
                p[1]! + t * (p[4]! - p[1]!),
                p[2]! + t * (p[5]! - p[2]!),
              ),
            );
          }
          const fast = segmentZoneDistance(zone, p, 0, 3, Infinity);
          return Math.abs(fast - brute) < 0.5;
        },
      ),
    );
  });
});

/** armtwin5's profile.json as shipped. */
function rawProfile(): Record<string, unknown> {
  const url = new URL('../../../public/models/armtwin5/profile.json', import.meta.url);
  return JSON.parse(fs.readFileSync(url, 'utf8')) as Record<string, unknown>;
}
