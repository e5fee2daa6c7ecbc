/**
 * What other parts need from a profile, in their own terms: the pulse-level servo table a
 * simulator runs (`armtwin sim --profile <name>`), a named pose as pulses, and, for an
 * `analytic5` profile, the `ArmProfile` that `solveIk` takes.
 */
import { US_PER_DEG, angleFromPwm } from '@armtwin/protocol';
import type { ArmProfile, ServoSpec } from '@armtwin/ik';
import { maxSpeedPwm, pwmFromServo, pwmLimits, servoLimits } from './convert.ts';
import type { Profile, ServoUnits } from './types.ts';

/** One servo as a simulator sees it: everything in pulses (µs). */
export interface ServoTableEntry {
  /** Wire id (`000` is 0). */
  readonly id: number;
  /** Three-digit wire id. */
  readonly key: string;
  readonly name: string;
  readonly type: 'revolute' | 'prismatic';
  /** What it speaks on the wire; an `angle` servo's pulses are exact §2 pulse-equivalents. */
  readonly units: ServoUnits;
  /** Mounting polarity (§2's k): turns an angle servo's pulse-equivalent into its angle. */
  readonly polarity: 1 | -1;
  /** Pulses of the joint limits, `minPwm ≤ maxPwm`; anything outside is refused. */
  readonly minPwm: number;
  readonly maxPwm: number;
  /** Fastest the pulse may change, µs per second. */
  readonly maxSpeedPwmPerS: number;
  /** The `home` pose, µs: where the servo starts. */
  readonly homePwm: number;
}

/** A named pose as pulses, in servo order; NaN where the pose leaves a servo be. */
export function posePwm(profile: Profile, pose: string): number[] | undefined {
  const values = profile.poses[pose];
  if (values === undefined) return undefined;
  return profile.servos.map((s, i) => {
    const v = values[i] ?? NaN;
    return Number.isNaN(v) ? NaN : pwmFromServo(s, v);
  });
}

/** The servo table of a parsed profile, in the profile's servo order. */
export function servoTable(profile: Profile): ServoTableEntry[] {
  const home = posePwm(profile, 'home') ?? [];
  return profile.servos.map((s, i) => {
    const { min, max } = pwmLimits(s);
    return {
      id: s.id,
      key: s.key,
      name: s.name,
      type: s.type,
      units: s.units,
      polarity: s.polarity,
      minPwm: min,
      maxPwm: max,
      maxSpeedPwmPerS: maxSpeedPwm(s),
      homePwm: home[i] ?? NaN,
    };
  });
}

/**
 * The `ArmProfile` of an `analytic5` profile (what `solveIk`, `forwardKinematics` and the 5-axis
 * simulator take), or undefined for a numeric one. Servo limits are servo angles; the §4 joint
 * offsets come from `ik.analytic5.jointOffsetsDeg` (servos after 003 get 0).
 */
export function armProfileFromProfile(profile: Profile): ArmProfile | undefined {
  const a = profile.ik.analytic5;
  if (profile.ik.kind !== 'analytic5' || a === undefined) return undefined;
  const servos: ServoSpec[] = profile.servos.map((s, i) => {
    const { min, max } = servoLimits(s);
    return {
      id: s.id,
      name: s.name,
      polarity: s.polarity,
      minDeg: min,
      maxDeg: max,
      jointOffsetDeg: a.jointOffsetsDeg[i] ?? 0,
      maxSpeedDegPerS: s.maxSpeed,
      ...(s.units === 'angle' ? { units: 'angle' as const } : {}),
    };
  });
  return { name: profile.title, links: { ...a.links }, servos };
}

/**
 * The `ArmProfile` of any profile in pulse terms: each servo's pulse limits and pulse speed
 * from `servoTable`, written as §2 angles with polarity +1, which round-trip to exactly the
 * same pulses (a prismatic axis included). What a servo model or the HUD's store counts in
 * for an arm the §4 solver does not describe. A servo that speaks angles (`units: "angle"`)
 * keeps its own servo angles instead (polarity, limits less the offset, speed), so that its
 * positions are never rounded to a pulse and may exceed the pulse range.
 */
export function pulseEquivalentArm(profile: Profile): ArmProfile {
  return {
    name: profile.title,
    links: { l0: 0, l1: 0, l2: 0, l3: 0 },
    servos: servoTable(profile).map((s, i): ServoSpec => {
      const p = profile.servos[i]!;
      if (p.units === 'angle') {
        const { min, max } = servoLimits(p);
        return {
          id: s.id,
          name: s.name,
          polarity: p.polarity,
          minDeg: min,
          maxDeg: max,
          jointOffsetDeg: 0,
          maxSpeedDegPerS: p.maxSpeed,
          units: 'angle',
        };
      }
      return {
        id: s.id,
        name: s.name,
        polarity: 1,
        minDeg: angleFromPwm(s.minPwm),
        maxDeg: angleFromPwm(s.maxPwm),
        jointOffsetDeg: 0,
        maxSpeedDegPerS: s.maxSpeedPwmPerS / US_PER_DEG,
      };
    }),
  };
}

/** The arm a servo model counts in: an `analytic5` profile's own, else the pulse-equivalent one. */
export const servoModelArm = (profile: Profile): ArmProfile =>
  armProfileFromProfile(profile) ?? pulseEquivalentArm(profile);
