/**
 * A robot arm's profile, declared once: link lengths and one spec per servo. The IK and FK read
 * everything arm-specific from here, so another arm with the same 5-axis layout (base yaw,
 * shoulder, elbow, wrist pitch, then wrist roll and gripper) is described by another profile.
 */
import { pwmFromAngle, type Polarity } from '@armtwin/protocol';

/** One servo. Angles are servo angles s in degrees relative to the servo's centre (§2). */
export interface ServoSpec {
  /** Servo id on the wire (`000` is 0); three digits when formatted. */
  readonly id: number;
  /** Human-readable name, shown by the HUD. */
  readonly name: string;
  /** Mounting polarity k of §2. */
  readonly polarity: Polarity;
  /** Lowest allowed servo angle, degrees. */
  readonly minDeg: number;
  /** Highest allowed servo angle, degrees. */
  readonly maxDeg: number;
  /**
   * Joint angle (as the kinematics of §4 measures it) at which the servo angle is 0:
   * `s = joint − jointOffsetDeg`. 90 for the shoulder (s001 = θ5 − 90), 0 for the others.
   */
  readonly jointOffsetDeg: number;
  /** Fastest the servo turns, degrees per second. */
  readonly maxSpeedDegPerS: number;
  /**
   * `angle` when the servo speaks §8 angle frames (a bus servo): its positions are servo
   * angles as they are, never rounded to a pulse. Absent: pulse widths.
   */
  readonly units?: 'angle';
}

/** Link lengths in mm (§4). */
export interface ArmLinks {
  /** Floor to shoulder axis. */
  readonly l0: number;
  /** Shoulder → elbow. */
  readonly l1: number;
  /** Elbow → wrist centre. */
  readonly l2: number;
  /** Wrist centre → gripper tip. */
  readonly l3: number;
}

export interface ArmProfile {
  readonly name: string;
  readonly links: ArmLinks;
  /**
   * Servos in id order. The IK uses the first four as base yaw, shoulder, elbow, wrist pitch;
   * the fifth is wrist roll and the sixth the gripper.
   */
  readonly servos: readonly ServoSpec[];
}

/** 60° per 0.16 s (§4). */
const DEMO_SPEED = 60 / 0.16;

function servo(id: number, name: string, minDeg: number, maxDeg: number, offset = 0): ServoSpec {
  return {
    id,
    name,
    polarity: 1,
    minDeg,
    maxDeg,
    jointOffsetDeg: offset,
    maxSpeedDegPerS: DEMO_SPEED,
  };
}

/**
 * The demo arm of PROTOCOL.md §4. Servo limits follow from §4's joint limits:
 * shoulder θ5 ∈ [0, 180] → s001 ∈ [−90, 90]; elbow θ4 ∈ [−135, 135]; wrist pitch
 * θ3 ∈ [−90, 90]; base and wrist roll ±135. §4 gives no gripper range: we choose
 * [0, 90], 0 = closed (1500 µs) and 90 = fully open (2167 µs).
 */
export const DEMO_ARM: ArmProfile = {
  name: 'armtwin 5-axis demo arm',
  links: { l0: 100, l1: 105, l2: 98, l3: 150 },
  servos: [
    servo(0, 'Base', -135, 135),
    servo(1, 'Shoulder', -90, 90, 90),
    servo(2, 'Elbow', -135, 135),
    servo(3, 'Wrist pitch', -90, 90),
    servo(4, 'Wrist roll', -135, 135),
    servo(5, 'Gripper', 0, 90),
  ],
};

/** Pulse range of a servo's angle limits, µs, `min ≤ max` whatever the polarity. */
export interface PwmRange {
  min: number;
  max: number;
}

/**
 * The pulse widths of the spec's angle limits (rounded as §2 rounds). Because rounding is
 * monotonic, every angle within the limits maps to a pulse within this range.
 */
export function servoLimitsPwm(spec: ServoSpec): PwmRange {
  const a = pwmFromAngle(spec.minDeg, spec.polarity);
  const b = pwmFromAngle(spec.maxDeg, spec.polarity);
  return a <= b ? { min: a, max: b } : { min: b, max: a };
}

/** The servo with this id (number, or the three-digit wire string), or undefined. */
/** Whether the servo speaks §8 angle frames (`units: 'angle'`). */
export const speaksAngle = (spec: ServoSpec | undefined): boolean => spec?.units === 'angle';

/** Whether a servo angle is one the servo may be sent: finite and within its limits. */
export function isAngleWithinLimits(id: number, deg: number, arm: ArmProfile = DEMO_ARM): boolean {
  const spec = findServo(id, arm);
  return spec !== undefined && Number.isFinite(deg) && deg >= spec.minDeg && deg <= spec.maxDeg;
}

export function findServo(id: number | string, arm: ArmProfile = DEMO_ARM): ServoSpec | undefined {
  if (typeof id === 'string' && !/^\d{3}$/.test(id)) return undefined;
  const n = Number(id);
  for (const spec of arm.servos) if (spec.id === n) return spec;
  return undefined;
}

/**
 * Whether `pwm` is a pulse the servo may be sent: a finite number inside `servoLimitsPwm`.
 * False for an id the arm does not have.
 */
export function isWithinLimits(
  id: number | string,
  pwm: number,
  arm: ArmProfile = DEMO_ARM,
): boolean {
  const spec = findServo(id, arm);
  if (spec === undefined || !Number.isFinite(pwm)) return false;
  const { min, max } = servoLimitsPwm(spec);
  return pwm >= min && pwm <= max;
}
