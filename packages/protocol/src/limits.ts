/** Field ranges of the wire contract, declared once. */
export const PWM_MIN = 500;
export const PWM_MAX = 2500;
export const PWM_CENTRE = 1500;
/** Degrees a servo turns over PWM_MIN…PWM_MAX. */
export const SERVO_RANGE_DEG = 270;
/** Pulse-width microseconds per degree of servo angle (2000 / 270 ≈ 7.407, §2). */
export const US_PER_DEG = (PWM_MAX - PWM_MIN) / SERVO_RANGE_DEG;
/** Largest |angle| in an angle frame `#IIIA±ddd.dd…!` (§8), degrees. */
export const ANGLE_DEG_MAX = 999.99;
export const SERVO_ID_MAX = 254;
/** `#255…` addresses every servo. */
export const SERVO_ID_ALL = 255;
export const MOVE_MS_MAX = 9999;
export const PING_SEQ_MAX = 4_294_967_295;
/** A frame longer than this (including its `!`) is dropped. */
export const MAX_FRAME_LENGTH = 64;
/** Largest |x|, |y|, |z| accepted in a `$KMS` frame, mm. */
export const KMS_COORD_MAX = 99_999;
/** Largest IK status code the reader accepts in `$KMS:c!` (room for codes beyond §4). */
export const KMS_CODE_MAX = 99;
/** The `$KMS` code for a solution a joint limit refuses (as the simulator answers it). */
export const KMS_LIMIT_CODE = 8;
/** The `$KMS` code for a solution below the floor: §4's code 1 (docs/protocol.md, "The floor"). */
export const KMS_FLOOR_CODE = 1;
/**
 * The `$KMS` code for a solution whose path takes a link into a keep-out zone or onto another
 * link: motion code 25 (docs/protocol.md, "Keep-out zones").
 */
export const KMS_ZONE_CODE = 25;
export const TEMP_MAX = 999;
/**
 * Largest supply voltage in a health frame, mV. Four digits up to 9999 mV as §1 shows; a supply
 * of 10 V or more (a 12 V Dynamixel bus) is written with five (`V12000`), up to 65 535 mV
 * (docs/protocol.md, "Health frames above 9.999 V").
 */
export const MV_MAX = 65_535;
