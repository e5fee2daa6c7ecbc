/**
 * The arm's links as segments for keep-out checks, from FK of a pulse vector: the base link
 * (base origin → first moving joint, fixed), then one link per moving part, joint origin to
 * joint origin and the last one to the tool point. On the 5-axis arm: base, upper arm,
 * forearm, hand (§4's shoulder, elbow, wrist and tip); on a URDF chain, the link each moving
 * joint carries, named after the joint. Scratch memory is made once per robot.
 */
import {
  armPoints,
  chainFkFrames,
  createArmPoints,
  createFkFrames,
  type FkFrames,
} from '@armtwin/ik';
import { jointFromServo, servoFromPwm } from '@armtwin/robot';
import { analyticJointsInto, type MotionRobot } from '../robot.ts';

export interface ArmLinks {
  /** Link names, for messages (`forearm`, `a3 link`). */
  readonly names: readonly string[];
  /** The URDF joint whose child link is this link (the ghost paints it), '' for the base. */
  readonly joints: readonly string[];
  /** Endpoints: link i runs from point i to point i + 1 (xyz at 3i), mm, base frame. */
  readonly points: Float64Array;
  /** Link 0 is the base: fixed, so only self-collision checks it. */
  readonly count: number;
}

interface Scratch {
  links: ArmLinks;
  q?: Float64Array;
  fk?: FkFrames;
}

const scratch = new WeakMap<MotionRobot, Scratch>();
const joints5 = { q0: 0, theta5: 0, theta4: 0, theta3: 0 };
const points5 = createArmPoints();

function create(robot: MotionRobot): Scratch {
  if (robot.kind === 'analytic5') {
    const j = robot.profile.servos.map((s) => s.joint);
    return {
      links: {
        names: ['base', 'upper arm', 'forearm', 'hand'],
        joints: ['', j[1] ?? '', j[2] ?? '', j[3] ?? ''],
        points: new Float64Array(15),
        count: 4,
      },
    };
  }
  const chain = robot.chain!;
  const names = ['base', ...chain.joints.map((j) => `${j.name} link`)];
  return {
    links: {
      names,
      joints: ['', ...chain.joints.map((j) => j.name)],
      points: new Float64Array(3 * (chain.dof + 2)),
      count: chain.dof + 1,
    },
    q: new Float64Array(chain.dof),
    fk: createFkFrames(chain),
  };
}

/**
 * The links of the pose of these pulses (profile servo order), or null when a servo of the
 * kinematic chain is unknown (NaN): such a pose cannot be checked (the limits refuse it).
 * The result is shared scratch, overwritten by the next call for the same robot.
 */
export function armLinks(robot: MotionRobot, pwm: ArrayLike<number>): ArmLinks | null {
  let s = scratch.get(robot);
  if (!s) scratch.set(robot, (s = create(robot)));
  const p = s.links.points;
  const servos = robot.profile.servos;
  if (robot.kind === 'analytic5') {
    if (!Object.values(analyticJointsInto(robot, pwm, joints5)).every(Number.isFinite)) return null;
    armPoints(joints5, robot.arm!, points5);
    p[0] = p[1] = p[2] = 0;
    const order = [points5.shoulder, points5.elbow, points5.wrist, points5.tip];
    order.forEach((v, k) => {
      p[3 * k + 3] = v.x;
      p[3 * k + 4] = v.y;
      p[3 * k + 5] = v.z;
    });
    return s.links;
  }
  const chain = robot.chain!;
  for (let k = 0; k < chain.dof; k++) {
    const j = chain.joints[k]!;
    const servo = servos[j.servoIndex]!;
    const v = jointFromServo(servo, servoFromPwm(servo, pwm[j.servoIndex]!));
    if (!Number.isFinite(v)) return null;
    s.q![k] = v;
  }
  const fk = chainFkFrames(chain, s.q!, s.fk!);
  p[0] = p[1] = p[2] = 0;
  p.set(fk.points, 3);
  const end = 3 * (chain.dof + 1);
  p[end] = fk.tip[12]!;
  p[end + 1] = fk.tip[13]!;
  p[end + 2] = fk.tip[14]!;
  return s.links;
}
