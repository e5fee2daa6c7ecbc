import { describe, expect, it } from 'vitest';
import { IK_CODES, ikCodeMessage, solveIk } from '../src/index.ts';
import { reference } from './reference.ts';

/**
 * Hand-picked targets [x, y, z, α]. `fails` lists every check the target fails, verified here
 * against an independent transcription of §4 (reference.ts); `code` is the first of them in
 * §4's order, which is what solveIk must report.
 */
const VECTORS: { name: string; target: [number, number, number, number]; fails: number[] }[] = [
  {
    name: 'home (0,0,453) α=90: fully stretched straight up passes with the 1e-9 slack',
    target: [0, 0, 453, 90],
    fails: [],
  },
  {
    name: 'code 1 before 6 and 7: (200,0,-10) α=0 puts the wrist at z=-10 (and the shoulder below 0)',
    target: [200, 0, -10, 0],
    fails: [1, 6, 7],
  },
  {
    name: 'code 1 before 2: (300,0,-50) α=0 is below the floor and 212 mm from the shoulder',
    target: [300, 0, -50, 0],
    fails: [1, 2, 3, 5],
  },
  {
    name: 'code 2 before 3: (500,0,100) α=0, wrist 350 mm out, more than L1+L2=203',
    target: [500, 0, 100, 0],
    fails: [2, 3, 5],
  },
  {
    name: 'code 2: (0,0,453) α=-90 points the gripper down from the top, wrist 503 mm away',
    target: [0, 0, 453, -90],
    fails: [2, 3, 5],
  },
  {
    name: 'code 3 (d = 0): (150,0,100) α=0 puts the wrist centre on the shoulder axis',
    target: [150, 0, 100, 0],
    fails: [3, 5],
  },
  {
    name: 'code 3 before 5: (153,0,100) α=0, wrist 3 mm from the shoulder, closer than L1-L2=7',
    target: [153, 0, 100, 0],
    fails: [3, 5],
  },
  {
    name: 'code 4: (200,0,100) α=0, wrist 50 mm from the shoulder needs the elbow at -151.8°',
    target: [200, 0, 100, 0],
    fails: [4],
  },
  {
    name: 'code 4 before 6: (110,0,110) α=0, elbow -156.9° and shoulder 234.8°',
    target: [110, 0, 110, 0],
    fails: [4, 6],
  },
  {
    name: 'code 6 (θ5 < 0): (330,0,10) α=0, the wrist 90 mm below the shoulder at 180 mm out',
    target: [330, 0, 10, 0],
    fails: [6],
  },
  {
    name: 'code 6 before 7 (θ5 > 180): (50,0,150) α=0, wrist behind the base axis',
    target: [50, 0, 150, 0],
    fails: [6, 7],
  },
  {
    name: 'code 7: (150,0,250) α=90, pointing up 150 mm out needs the wrist at 134.2°',
    target: [150, 0, 250, 90],
    fails: [7],
  },
  {
    name: 'code 7 before 8: (-100,5,350) α=90, wrist 92.9° and base yaw 177.1°',
    target: [-100, 5, 350, 90],
    fails: [7, 8],
  },
  {
    name: 'code 8 (ours, base limit): (-150,-10,300) α=60 passes §4 but needs base yaw -176.2°',
    target: [-150, -10, 300, 60],
    fails: [8],
  },
  {
    name: 'base yaw -90° is inside ±135: (0,-200,200) α=0 passes',
    target: [0, -200, 200, 0],
    fails: [],
  },
];

describe('solveIk status codes, first failing check in order 1,2,3,5,4,6,7 then 8', () => {
  it.each(VECTORS)('$name', ({ target, fails }) => {
    expect(reference(...target).fails).toEqual(fails);
    const r = solveIk(...target);
    expect(r.code).toBe(fails[0] ?? 0);
    expect(r.alpha).toBe(target[3]);
    if (r.code === 0) {
      expect(r.pwm.every(Number.isInteger)).toBe(true);
    } else {
      expect(r.pwm.every(Number.isNaN)).toBe(true);
    }
  });

  it('home pose: code 0, all servo angles 0, pwm 1500 ×4', () => {
    const r = solveIk(0, 0, 453, 90);
    expect(r.code).toBe(0);
    for (const s of r.servoAngles) expect(s).toBeCloseTo(0, 9);
    expect(r.pwm).toEqual([1500, 1500, 1500, 1500]);
  });

  it('a limit failure keeps the rejected joints (for drawing); a no-triangle failure has NaN', () => {
    const limit = solveIk(200, 0, 100, 0);
    expect(limit.joints.theta4).toBeCloseTo(-151.75158, 4);
    expect(limit.servoAngles[2]).toBeCloseTo(-151.75158, 4);
    const far = solveIk(500, 0, 100, 0);
    expect(far.joints.q0).toBe(0);
    expect([far.joints.theta5, far.joints.theta4, far.joints.theta3].every(Number.isNaN)).toBe(
      true,
    );
  });

  it('code 5 is unreachable here: |cos A| ≤ 1 and |cos β| ≤ 1 are both |L1-L2| ≤ d ≤ L1+L2', () => {
    for (let d = 0; d <= 8; d += 0.001) {
      const code = solveIk(150 + d, 0, 100, 0).code; // wrist centre d mm from the shoulder
      expect(code).not.toBe(5);
      if (d < 6.999) expect(code).toBe(3);
      if (d > 7.001) expect(code).toBe(4); // a triangle, but the elbow folds past -135°
    }
  });

  it('non-finite input is code 2, out of reach', () => {
    expect(solveIk(NaN, 0, 0, 0).code).toBe(2);
    expect(solveIk(0, Infinity, 0).code).toBe(2);
    expect(solveIk(0, 0, 300, NaN).code).toBe(2);
  });

  it('IK_CODES has words for 0–8', () => {
    expect(Object.keys(IK_CODES).map(Number)).toEqual([0, 1, 2, 3, 4, 5, 6, 7, 8]);
    expect(ikCodeMessage(2)).toBe('out of reach');
    expect(ikCodeMessage(42)).toBe('unknown code 42');
  });
});

describe('α search: −90, −89, …, 90, first that passes, else the code of α = −90', () => {
  it.each([
    [300, 0, 100, -37],
    [40, 0, 300, 15],
    [250, 0, -40, -71],
  ])('(%d,%d,%d) is first reachable at α=%d', (x, y, z, expected) => {
    const r = solveIk(x, y, z);
    expect(r.code).toBe(0);
    expect(r.alpha).toBe(expected);
    for (let a = -90; a < expected; a++) expect(solveIk(x, y, z, a).code).not.toBe(0);
    expect(r.pwm).toEqual(solveIk(x, y, z, expected).pwm);
  });

  it('(100,0,0) is reachable straight down, so the search stops at α=-90', () => {
    expect(solveIk(100, 0, 0)).toMatchObject({ code: 0, alpha: -90 });
  });

  it.each([
    ['(20,0,20): α=-90 hits the elbow limit, most other pitches are below the floor', 20, 0, 20, 4],
    ['(0,0,150): α=-90 hits the wrist limit, most others the shoulder limit', 0, 0, 150, 7],
    ['(-200,10,200): 53 pitches fail only the base limit, α=-90 is out of reach', -200, 10, 200, 2],
  ])('unreachable %s', (_name, x, y, z, code) => {
    const r = solveIk(x, y, z);
    expect(r.code).toBe(code);
    expect(r.alpha).toBe(-90);
    expect(r).toEqual(solveIk(x, y, z, -90));
  });
});
