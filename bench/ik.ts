/**
 * Section 5: IK solves per second in this process (no services). Targets are the forward
 * kinematics of random reachable joint sets (fixed seed), so every analytic solve takes the
 * full path. Each variant runs for a fixed time in batches of the whole target set, in three
 * interleaved rounds; the median round counts. Baseline: forward kinematics of the same poses.
 */
import {
  createIkResult,
  forwardKinematics,
  solveIk,
  solveIkInto,
  ALPHA_SEARCH_FROM,
  type Joints,
  type Pose,
} from '@armtwin/ik';
import { round } from './lib/stats.ts';
import type { Row, Section, SectionOutput } from './lib/types.ts';

/** mulberry32: a small seeded PRNG, so every run solves the same targets. */
function rng(seed: number) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

function targets(n: number) {
  const r = rng(20260601);
  const poses: Pose[] = [];
  const joints: Joints[] = [];
  const out = createIkResult();
  for (let guard = 0; poses.length < n && guard < n * 100; guard++) {
    const j = {
      q0: -135 + 270 * r(),
      theta5: 180 * r(),
      theta4: -135 * r(),
      theta3: -90 + 180 * r(),
    };
    const p = forwardKinematics(j);
    if (solveIkInto(out, p.x, p.y, p.z, p.alpha).code !== 0) continue;
    poses.push({ ...p });
    joints.push(j);
  }
  return { poses, joints };
}

/** Calls `body` over all targets repeatedly for `ms`; returns calls per second. */
function rate(count: number, ms: number, body: () => number): { perS: number; sink: number } {
  let calls = 0;
  let sink = 0;
  const t0 = process.hrtime.bigint();
  const stop = t0 + BigInt(Math.round(ms * 1e6));
  let now = t0;
  for (let batch = 0; batch < 1e7 && now < stop; batch++) {
    sink += body();
    calls += count;
    now = process.hrtime.bigint();
  }
  return { perS: calls / (Number(now - t0) / 1e9), sink };
}

const median = (xs: number[]) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)]!;
const k = (v: number) => `${Math.round(v).toLocaleString('en')}/s`;

export const ikSection: Section = {
  id: 'ik',
  title: 'IK solves per second (@armtwin/ik)',
  async run(ctx): Promise<SectionOutput> {
    const n = 1000;
    const ms = ctx.quick ? 300 : 1000;
    const { poses, joints } = targets(n);
    const res = createIkResult();
    const fk: Pose = { x: 0, y: 0, z: 0, alpha: 0 };
    let tries = 0;
    for (const p of poses) tries += solveIkInto(res, p.x, p.y, p.z).alpha - ALPHA_SEARCH_FROM + 1;
    const variants: Record<string, () => number> = {
      fk: () => {
        let s = 0;
        for (const j of joints) s += forwardKinematics(j, undefined, fk).x;
        return s;
      },
      analyticInto: () => {
        let s = 0;
        for (const p of poses) s += solveIkInto(res, p.x, p.y, p.z, p.alpha).code;
        return s;
      },
      analyticAlloc: () => {
        let s = 0;
        for (const p of poses) s += solveIk(p.x, p.y, p.z, p.alpha).code;
        return s;
      },
      search: () => {
        let s = 0;
        for (const p of poses) s += solveIkInto(res, p.x, p.y, p.z).code;
        return s;
      },
    };
    const rounds: Record<string, number[]> = Object.fromEntries(
      Object.keys(variants).map((v) => [v, []]),
    );
    let sink = 0;
    for (const body of Object.values(variants)) sink += rate(poses.length, 100, body).sink; // warm-up / JIT
    for (let r = 0; r < 3; r++) {
      for (const [name, body] of Object.entries(variants)) {
        const x = rate(poses.length, ms, body);
        rounds[name]!.push(x.perS);
        sink += x.sink;
      }
    }
    const m = Object.fromEntries(
      Object.entries(rounds).map(([v, xs]) => [v, median(xs)]),
    ) as Record<string, number>;
    const meanTries = tries / poses.length;
    const rows: Row[] = [
      {
        figure: 'IK analytic, fixed α (solveIkInto)',
        value: k(m.analyticInto!),
        baseline: `FK ${k(m.fk!)}`,
        target: 'reported',
        met: null,
      },
      {
        figure: 'IK analytic, fixed α (solveIk, allocating)',
        value: k(m.analyticAlloc!),
        baseline: `solveIkInto ${k(m.analyticInto!)}`,
        target: 'reported',
        met: null,
      },
      {
        figure: `IK with α search (mean ${meanTries.toFixed(1)} α tried)`,
        value: k(m.search!),
        baseline: `analytic ${k(m.analyticInto!)}`,
        target: 'reported',
        met: null,
      },
    ];
    return {
      rows,
      settings: { targets: poses.length, msPerRound: ms, rounds: 3, seed: 20260601 },
      data: {
        solvesPerS: Object.fromEntries(Object.entries(m).map(([v, x]) => [v, Math.round(x)])),
        rounds: Object.fromEntries(
          Object.entries(rounds).map(([v, xs]) => [v, xs.map((x) => Math.round(x))]),
        ),
        meanAlphaTries: round(meanTries, 2),
        sink: Number.isFinite(sink),
      },
    };
  },
};
