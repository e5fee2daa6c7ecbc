/**
 * The simulated controller's `$KMS` (PROTOCOL.md §4): where each servo goes and the code it
 * answers, with another arm's IK (profile.ts) when the model has one, else the demo arm's
 * analytic IK on servos 000–003 with the joint limits. Pure: the keep-out check is handed in
 * (it counts its own refusals in the model).
 */
import { isWithinLimits, solveIk, type ArmProfile } from '@armtwin/ik';
import { KMS_LIMIT_CODE } from '@armtwin/protocol';
import type { SimModelOptions } from './options.ts';
import type { Servos } from './servos.ts';

export interface KmsOutcome {
  /** The `$KMS:c!` code: 0 = moving. */
  code: number;
  /** Counted as an IK refusal. */
  ikRefused: boolean;
  /** The servos to move (by index) and their pulses; empty unless the code is 0. */
  moves: { i: number; pwm: number }[];
}

export function solveKms(
  x: number,
  y: number,
  z: number,
  alpha: number | undefined,
  t: number,
  s: Servos,
  arm: ArmProfile,
  solver: SimModelOptions['kms'],
  keepOutCode: (pwm: readonly number[]) => number,
): KmsOutcome {
  if (solver) {
    // Another arm's IK: every servo it gives a pulse moves, together.
    const now = Array.from({ length: s.count }, (_, i) => s.pwmAt(i, t));
    const k = solver(x, y, z, alpha, now);
    const code = k.code === 0 ? keepOutCode(k.pwm) : k.code;
    const moves: KmsOutcome['moves'] = [];
    if (code === 0)
      k.pwm.forEach((p, i) => Number.isNaN(p) || moves.push({ i, pwm: Math.round(p) }));
    return { code, ikRefused: code !== 0, moves };
  }
  const r = solveIk(x, y, z, alpha, arm);
  const idx = [0, 1, 2, 3].map((j) => s.indexOf(arm.servos[j]?.id ?? -1));
  const ok =
    r.code === 0 && idx.every((i, j) => i >= 0 && isWithinLimits(s.ids[i]!, r.pwm[j]!, arm));
  const sol = new Array<number>(s.count).fill(NaN);
  idx.forEach((i, j) => (sol[i] = r.pwm[j]!));
  const low = ok ? keepOutCode(sol) : 0;
  return {
    code: low || (r.code === 0 && !ok ? KMS_LIMIT_CODE : r.code),
    ikRefused: r.code !== 0,
    moves: !ok || low ? [] : idx.map((i, j) => ({ i, pwm: r.pwm[j]! })),
  };
}
