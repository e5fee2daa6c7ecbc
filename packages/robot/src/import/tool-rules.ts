/**
 * What the import takes for the tool (docs/robots.md, "How the profile is derived"):
 * - a **tool frame**: a link hung on a `fixed` joint and named like a tool or gripper frame
 *   (`gripper_frame_link`, `tool_frame`, `grasp_point`, …), made by the URDF's author for the
 *   tool centre; it wins over the deepest link;
 * - **tool joints**: a jaw or finger joint at the end of a chain (named so, or moving a link
 *   named so, with no driven joint beyond it): a servo, jogged, but outside the IK chain, so
 *   a Cartesian move leaves it where it is and opening the jaw never moves the tool centre;
 * - **servo ids** from the URDF's `<transmission>` actuators when they are numbered
 *   (`motor1` … `motor6`: the bus ids the arm's makers gave them, as LeRobot's SO-101).
 */
import type { UrdfJoint } from '../urdf/urdf.ts';

/** Link names taken for a tool frame (on a fixed joint), after the tool-centre names. */
export const TOOL_FRAME_NAMES: readonly RegExp[] = [
  /(^|[_-])(tool|gripper|grasp(ing)?|hand|ee)_?(frame|point|tip)(_link)?$/i,
];
/** A joint (or the link it moves) named like a jaw or a finger. */
export const TOOL_JOINT_NAME = /jaw|finger|gripper|grip|claw|pinch/i;

const driven = (j: UrdfJoint) =>
  (j.type === 'revolute' || j.type === 'continuous' || j.type === 'prismatic') &&
  j.mimic === undefined;

/** The links below `link` (itself included), through `joints`. */
function subtree(link: string, joints: readonly UrdfJoint[]): UrdfJoint[] {
  const out: UrdfJoint[] = [];
  const todo = [link];
  while (todo.length) {
    const l = todo.pop()!;
    for (const j of joints)
      if (j.parent === l && !out.includes(j)) {
        out.push(j);
        todo.push(j.child);
      }
  }
  return out;
}

/** The tool joints: driven jaw or finger joints with no driven joint beyond them. */
export function toolJoints(joints: readonly UrdfJoint[]): UrdfJoint[] {
  return joints.filter(
    (j) =>
      driven(j) &&
      (TOOL_JOINT_NAME.test(j.name) || TOOL_JOINT_NAME.test(j.child)) &&
      !subtree(j.child, joints).some(driven),
  );
}

/** Links that move with a tool joint (its child and everything below): never the tool centre. */
export function linksBeyond(
  tools: readonly UrdfJoint[],
  joints: readonly UrdfJoint[],
): Set<string> {
  const out = new Set<string>();
  for (const t of tools) {
    out.add(t.child);
    for (const j of subtree(t.child, joints)) out.add(j.child);
  }
  return out;
}

/** Whether `link` hangs on a fixed joint and is named like a tool frame. */
export function isToolFrame(link: string, joints: readonly UrdfJoint[], re: RegExp): boolean {
  return re.test(link) && joints.some((j) => j.child === link && j.type === 'fixed');
}

/**
 * Servo ids from numbered `<transmission>` actuators (`<actuator name="motor3">` → 3), for the
 * joints given; undefined unless every one of them has its own id in 0–254.
 */
export function transmissionIds(urdf: string, joints: readonly string[]): number[] | undefined {
  const byJoint = new Map<string, number>();
  const text = urdf.replace(/<!--[\s\S]*?-->/g, '');
  for (const m of text.matchAll(/<transmission\b[\s\S]*?<\/transmission>/g)) {
    const joint = /<joint\b[^>]*\bname\s*=\s*["']([^"']+)["']/.exec(m[0])?.[1];
    const actuator = /<actuator\b[^>]*\bname\s*=\s*["'][^"']*?(\d+)["']/.exec(m[0])?.[1];
    if (joint !== undefined && actuator !== undefined) byJoint.set(joint, Number(actuator));
  }
  const ids = joints.map((j) => byJoint.get(j));
  const ok = ids.every((id) => id !== undefined && id <= 254) && new Set(ids).size === ids.length;
  return ok ? (ids as number[]) : undefined;
}
