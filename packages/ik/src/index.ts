/**
 * @armtwin/ik: the analytic IK and FK of the 5-axis arm (PROTOCOL.md §4) and the numeric IK of
 * any serial chain. No I/O.
 */
export {
  DEMO_ARM,
  findServo,
  isAngleWithinLimits,
  isWithinLimits,
  servoLimitsPwm,
  speaksAngle,
  type ArmLinks,
  type ArmProfile,
  type PwmRange,
  type ServoSpec,
} from './arm.ts';
export {
  armPoints,
  createArmPoints,
  forwardKinematics,
  jointsFromServoAngles,
  pwmFromJoints,
  servoAnglesFromJoints,
  type ArmPoints,
  type Joints,
  type Pose,
  type Quad,
  type Vec3,
} from './fk.ts';
export {
  ALPHA_SEARCH_FROM,
  ALPHA_SEARCH_TO,
  IK_CODES,
  IK_TOLERANCE,
  createIkResult,
  ikCodeMessage,
  solveIk,
  solveIkInto,
  type IkCode,
  type IkResult,
} from './ik.ts';
export * from './numeric/index.ts';
