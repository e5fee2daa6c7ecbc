/**
 * What the HUD needs from a robot profile, in its own terms. Pure: no DOM, no three.js.
 *
 * - `storeArm`: the `ArmProfile` the store counts in. An `analytic5` profile gives its own
 *   (armtwin5's equals DEMO_ARM, so the 5-axis HUD is unchanged); any other profile a
 *   pulse-equivalent one, as `armtwin sim` does (apps/cli/src/sim/profile.ts): each servo's pulse
 *   limits written as §2 angles with polarity +1, which round-trip to exactly the same pulses,
 *   a prismatic axis included. So the store's "angles" are always linear in pulses.
 * - `joints`: per servo, the URDF joint and the linear map store angle → URDF joint value
 *   (radians, or metres for a prismatic axis): `value = scale·angle + bias`.
 * - `sliders`: the jog sliders, in joint units (degrees, or millimetres for a prismatic axis).
 */
import { type ArmProfile } from '@armtwin/ik';
import {
  jointFromPwm,
  pwmFromServo,
  servoFromPwm,
  servoModelArm,
  type Profile,
  type ProfileServo,
} from '@armtwin/robot';
import { PWM_CENTRE, PWM_MAX, PWM_MIN, SERVO_RANGE_DEG } from '@armtwin/protocol';

const US_PER_DEG = (PWM_MAX - PWM_MIN) / SERVO_RANGE_DEG;

export interface JointMap {
  /** URDF joint driven by servo i (profile order). */
  readonly names: readonly string[];
  /** URDF joint value = scale[i]·angle + bias[i], angle in the store's degrees. */
  readonly scale: Float64Array;
  readonly bias: Float64Array;
}

export interface SliderSpec {
  /** Index in the profile (and store) servo order. */
  readonly index: number;
  /** Wire id. */
  readonly id: number;
  readonly name: string;
  readonly unit: 'deg' | 'mm';
  /** Joint limits in joint units (the profile's `min`, `max`). */
  readonly min: number;
  readonly max: number;
  /** Slider step, joint units. */
  readonly step: number;
  /** The servo speaks §8 angle frames: its pulses are exact, unrounded pulse-equivalents. */
  readonly speaksAngle: boolean;
  /** Joint value (deg or mm) of a store angle (`ArmStore.angle`); NaN for NaN. */
  valueFromAngle(angle: number): number;
  /** Joint value (deg or mm) of a pulse; NaN for NaN. */
  valueFromPwm(pwm: number): number;
  /** Pulse (integer µs; an angle servo's exact pulse-equivalent) of a joint value. */
  pwmFromValue(value: number): number;
}

export interface RobotSpec {
  readonly profile: Profile;
  readonly name: string;
  readonly title: string;
  /** The URDF, relative to the page: `models/<name>/<urdf>`. */
  readonly urdfUrl: string;
  readonly storeArm: ArmProfile;
  readonly joints: JointMap;
  readonly sliders: readonly SliderSpec[];
}

/** Slider step of a prismatic axis, mm (the track6 track is 1.5 mm per µs). */
export const PRISMATIC_STEP_MM = 5;

/** The arm the store counts in (the same as `armtwin sim`'s servo model). */
export const storeArmFor = servoModelArm;

/** Exact pulse (µs, unrounded) of a store angle: the inverse of `angleFromPwm`. */
export const pwmOfStoreAngle = (angle: number, polarity: number): number =>
  PWM_CENTRE + polarity * US_PER_DEG * angle;

export function jointMap(profile: Profile, arm: ArmProfile): JointMap {
  const n = profile.servos.length;
  const scale = new Float64Array(n);
  const bias = new Float64Array(n);
  profile.servos.forEach((s, i) => {
    const k = arm.servos[i]?.polarity ?? 1;
    const at = (angle: number) => jointFromPwm(s, pwmOfStoreAngle(angle, k));
    bias[i] = at(0);
    scale[i] = at(1) - bias[i]!;
  });
  return { names: profile.servos.map((s) => s.joint), scale, bias };
}

/** Joint value (deg or mm) of a pulse: servo value plus the revolute offset. */
function jointUnits(s: ProfileServo, pwm: number): number {
  const v = servoFromPwm(s, pwm);
  return s.type === 'revolute' ? v + s.offset : v;
}

export function sliderSpecs(
  profile: Profile,
  arm: ArmProfile = storeArmFor(profile),
): SliderSpec[] {
  return profile.servos.map((s, index) => {
    const k = arm.servos[index]?.polarity ?? 1;
    const angle = s.units === 'angle';
    return {
      index,
      id: s.id,
      name: s.name,
      unit: s.type === 'revolute' ? 'deg' : 'mm',
      min: s.min,
      max: s.max,
      step: s.type === 'revolute' ? 1 : PRISMATIC_STEP_MM,
      speaksAngle: angle,
      // An angle servo's store angle is its servo angle: the joint is that plus the offset,
      // with no pulse on the way (±360° stays ±360°).
      valueFromAngle: angle
        ? (a: number) => a + s.offset
        : (a: number) => jointUnits(s, pwmOfStoreAngle(a, k)),
      valueFromPwm: (pwm: number) => jointUnits(s, pwm),
      pwmFromValue: angle
        ? (value: number) => pwmOfStoreAngle(value - s.offset, k)
        : (value: number) => pwmFromServo(s, s.type === 'revolute' ? value - s.offset : value),
    };
  });
}

/** The HUD's view of a parsed profile. */
export function robotSpec(profile: Profile): RobotSpec {
  const storeArm = storeArmFor(profile);
  return {
    profile,
    name: profile.name,
    title: profile.title,
    urdfUrl: `models/${profile.name}/${profile.urdf}`,
    storeArm,
    joints: jointMap(profile, storeArm),
    sliders: sliderSpecs(profile, storeArm),
  };
}
