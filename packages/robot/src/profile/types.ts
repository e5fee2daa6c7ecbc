/**
 * A robot profile (`public/models/<name>/profile.json`), as `parseProfile` returns it: one
 * entry per servo mapping the servo's wire id to a URDF joint, its pulse mapping, limits and
 * speed, plus the IK kind and named poses. docs/robots.md describes the JSON format.
 *
 * Units: a revolute servo's values are degrees, a prismatic one's millimetres. The URDF (and
 * the numeric IK's joint vector) uses radians and metres; `jointFromServo` and friends convert.
 */

/** The value of the profile's `format` field this parser reads. */
export const PROFILE_FORMAT = 'armtwin-profile/1';

export type ServoKind = 'revolute' | 'prismatic';

/**
 * What a servo speaks on the wire: `pulse` (§2 pulse widths, `#IIIP…`) or `angle` (§8 angle
 * frames `#IIIA±ddd.dd…`, bus servos such as Dynamixel or Feetech). Declared once.
 */
export const SERVO_UNITS = ['pulse', 'angle'] as const;
export type ServoUnits = (typeof SERVO_UNITS)[number];

/** Optional servo fields and their values when a profile leaves them out (declared once). */
export const PROFILE_SERVO_DEFAULTS = {
  /** Mounting polarity k of PROTOCOL.md §2. */
  polarity: 1,
  /** Joint value (deg) at servo angle 0: `joint = s + offset`. Revolute only. */
  offset: 0,
  /** Lowest pulse the servo accepts, µs. */
  pulseMin: 500,
  /** Highest pulse the servo accepts, µs. */
  pulseMax: 2500,
  /** What the servo speaks on the wire. */
  units: 'pulse',
} as const;

export interface ProfileServo {
  /** Wire id (`000` is 0). */
  readonly id: number;
  /** The id as the wire writes it: three digits. */
  readonly key: string;
  /** Human-readable name, shown by the HUD. */
  readonly name: string;
  /** The URDF joint this servo drives. */
  readonly joint: string;
  readonly type: ServoKind;
  /**
   * `pulse`: positions travel as pulse widths, so the limits must fit the pulse range.
   * `angle`: positions travel as §8 angle frames in servo degrees (revolute only); the limits
   * may span up to ±999.99° of servo angle and `pulseMin`/`pulseMax` do not apply.
   */
  readonly units: ServoUnits;
  /** Mounting polarity: +1, or −1 when a higher pulse turns (or moves) the joint negative. */
  readonly polarity: 1 | -1;
  /**
   * Revolute: joint angle (URDF value, degrees) at servo angle 0, so `joint = s + offset`.
   * Prismatic: always 0 (the pulse range maps straight onto the joint limits).
   */
  readonly offset: number;
  /** Pulse range the servo accepts, µs. A prismatic axis spans its limits across it. */
  readonly pulseMin: number;
  readonly pulseMax: number;
  /** Joint limits in joint units: degrees (revolute) or millimetres (prismatic). */
  readonly min: number;
  readonly max: number;
  /** Speed limit, degrees or millimetres per second. */
  readonly maxSpeed: number;
}

/** Link lengths (mm) and §4 joint offsets of the analytic 5-axis solver. */
export interface Analytic5Spec {
  readonly links: {
    readonly l0: number;
    readonly l1: number;
    readonly l2: number;
    readonly l3: number;
  };
  /**
   * §4 joint angle minus servo angle for servos 000–003 (DEMO_ARM's `jointOffsetDeg`):
   * `[0, 90, 0, 0]` on the demo arm, because θ5 = s001 + 90.
   */
  readonly jointOffsetsDeg: readonly [number, number, number, number];
}

export interface ProfileIk {
  readonly kind: 'analytic5' | 'numeric';
  /** URDF link the chain starts at (world frame). */
  readonly baseLink: string;
  /** URDF link whose frame is the tool (the tip the IK places). */
  readonly tipLink: string;
  /** Present when kind is `analytic5`. */
  readonly analytic5?: Analytic5Spec;
  /**
   * The floor, mm: the plane z = floorZ of the base frame, which no pose may put the tool point
   * or a joint origin below (`checkFloor` of @armtwin/motion). Absent: `DEFAULT_FLOOR_Z` (0).
   */
  readonly floorZ?: number;
}

/** The shapes a keep-out zone can take (docs/robots.md, "Keep-out zones"). Declared once. */
export const ZONE_SHAPES = ['box', 'cylinder', 'plane'] as const;
export type ZoneShape = (typeof ZONE_SHAPES)[number];

/** A keep-out zone, mm in the arm's base frame (the frame of `ik.baseLink`, z up). */
export type Zone =
  | {
      readonly name: string;
      readonly shape: 'box';
      /** Axis-aligned corners, each component of `min` below that of `max`. */
      readonly min: readonly [number, number, number];
      readonly max: readonly [number, number, number];
    }
  | {
      readonly name: string;
      readonly shape: 'cylinder';
      /** A vertical cylinder: axis through (x, y), radius > 0, from zMin up to zMax. */
      readonly center: readonly [number, number];
      readonly radius: number;
      readonly zMin: number;
      readonly zMax: number;
    }
  | {
      readonly name: string;
      readonly shape: 'plane';
      /** A half-space: every point p with (p − point)·normal > 0 is kept out. */
      readonly point: readonly [number, number, number];
      /** Unit length (the parser normalises it). */
      readonly normal: readonly [number, number, number];
    };

/** Keep-out settings of a profile (`keepOut`): zones and the links' collision size. */
export interface ProfileKeepOut {
  /** Zones no link may enter. */
  readonly zones: readonly Zone[];
  /** Radius of every link's capsule, mm; absent: `DEFAULT_ZONE_OPTIONS.linkRadius` of @armtwin/motion. */
  readonly linkRadius?: number;
  /** Whether non-adjacent links are checked against each other; absent: true. */
  readonly selfCollision?: boolean;
}

export interface Profile {
  /** Folder name under public/models, `[a-z0-9-_]+`. */
  readonly name: string;
  readonly title: string;
  /** URDF file name, relative to the profile's folder. */
  readonly urdf: string;
  readonly ik: ProfileIk;
  /** In the order the profile lists them (the sim streams them in this order). */
  readonly servos: readonly ProfileServo[];
  /**
   * Named poses as servo values (§2 servo angle s in degrees, or mm for a prismatic axis), one
   * per servo in `servos` order; NaN where the pose leaves a servo where it is. `home` is always
   * present and complete. `posePwm` turns one into pulses.
   */
  readonly poses: Readonly<Record<string, readonly number[]>>;
  /** Keep-out zones and link size; absent: no zones (the floor and self-collision still apply). */
  readonly keepOut?: ProfileKeepOut;
}

export type ParseProfileResult =
  | { readonly ok: true; readonly profile: Profile }
  | { readonly ok: false; readonly errors: string[] };
