/** Shared by the numeric-* and profile-* tests: the shipped profiles and chains, a seeded RNG. */
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chainFromUrdf, parseProfile, type Profile } from '../src/index.ts';
import { type Chain } from '@armtwin/ik';

export const MODELS = path.resolve(fileURLToPath(import.meta.url), '../../../../public/models');

export function readModelFile(name: string, file: string): string {
  return fs.readFileSync(path.join(MODELS, name, file), 'utf8');
}

export interface Robot {
  profile: Profile;
  chain: Chain;
  urdf: string;
}

/** Parse a shipped profile and build its chain; throws with the messages when either fails. */
export function loadRobot(name: string): Robot {
  const parsed = parseProfile(JSON.parse(readModelFile(name, 'profile.json')));
  if (!parsed.ok) throw new Error(parsed.errors.join('\n'));
  const urdf = readModelFile(name, parsed.profile.urdf);
  const built = chainFromUrdf(parsed.profile, urdf);
  if (!built.ok) throw new Error(built.errors.join('\n'));
  return { profile: parsed.profile, chain: built.chain, urdf };
}

/** Deterministic pseudo-random numbers in [0, 1) (mulberry32), so a failure reproduces. */
export function rng(seed: number): () => number {
  let a = seed;
  return () => {
    a = (a + 0x6d2b79f5) | 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

/** Uniform joint values within the chain's limits. */
export function randomJoints(chain: Chain, next: () => number): Float64Array {
  return Float64Array.from(chain.lower, (lo, i) => lo + next() * (chain.upper[i]! - lo));
}

/** Distance (mm) between two transforms' origins and the angle (degrees) between their rotations. */
export function poseDistance(
  a: ArrayLike<number>,
  b: ArrayLike<number>,
): { mm: number; deg: number } {
  const mm = Math.hypot(a[12]! - b[12]!, a[13]! - b[13]!, a[14]! - b[14]!);
  let trace = 0; // trace(Raᵀ Rb) = Σ columns' dot products
  for (let c = 0; c < 3; c++) for (let r = 0; r < 3; r++) trace += a[c * 4 + r]! * b[c * 4 + r]!;
  const deg = (Math.acos(Math.max(-1, Math.min(1, (trace - 1) / 2))) * 180) / Math.PI;
  return { mm, deg };
}

/** Angle (degrees) between two transforms' z axes (the tool axis). */
export function axisAngle(a: ArrayLike<number>, b: ArrayLike<number>): number {
  const dot = a[8]! * b[8]! + a[9]! * b[9]! + a[10]! * b[10]!;
  return (Math.acos(Math.max(-1, Math.min(1, dot))) * 180) / Math.PI;
}

/** Whether every joint value is within the chain's limits (1e-9 slack). */
export function withinLimits(chain: Chain, q: ArrayLike<number>): boolean {
  for (let i = 0; i < chain.dof; i++) {
    const v = q[i]!;
    if (!(v >= chain.lower[i]! - 1e-9 && v <= chain.upper[i]! + 1e-9)) return false;
  }
  return true;
}
