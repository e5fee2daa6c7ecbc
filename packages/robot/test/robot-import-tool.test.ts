/**
 * The import's tool rules on small URDFs shaped like the SO-100/SO-101 descriptions: a fixed
 * link named like a gripper frame is the tool centre (not the moving jaw), a jaw at the end of
 * the chain is a tool joint outside the IK chain, and numbered `<transmission>` actuators give
 * the servo ids (motor1 → 001).
 */
import { describe, expect, test } from 'vitest';
import { deriveProfile, toolJoints, transmissionIds } from '../src/index.ts';
import { parseUrdfJoints } from '../src/urdf/urdf.ts';

const joint = (name: string, type: string, parent: string, child: string) =>
  `<joint name="${name}" type="${type}"><parent link="${parent}"/><child link="${child}"/>` +
  `<origin xyz="0 0 0.1" rpy="0 0 0"/><axis xyz="0 0 1"/>` +
  (type === 'fixed' ? '' : '<limit lower="-1.5" upper="1.5" velocity="2" effort="1"/>') +
  `</joint>`;
const trans = (j: string, motor: string) =>
  `<transmission name="${j}_trans"><type>transmission_interface/SimpleTransmission</type>` +
  `<joint name="${j}"><hardwareInterface>x</hardwareInterface></joint>` +
  `<actuator name="${motor}"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>`;

/** An SO-101 shape: pan, lift, wrist roll; a jaw beside a fixed gripper frame. */
const SO = (frame = 'gripper_frame_link', motors = ['motor1', 'motor2', 'motor3', 'motor4']) => `
<robot name="so">
  <link name="base_link"/><link name="shoulder"/><link name="arm"/><link name="gripper_link"/>
  <link name="${frame}"/><link name="moving_jaw_link"/>
  ${joint('shoulder_pan', 'revolute', 'base_link', 'shoulder')}
  ${joint('shoulder_lift', 'revolute', 'shoulder', 'arm')}
  ${joint('wrist_roll', 'revolute', 'arm', 'gripper_link')}
  ${joint('gripper', 'revolute', 'gripper_link', 'moving_jaw_link')}
  ${joint('gripper_frame_joint', 'fixed', 'gripper_link', frame)}
  ${trans('gripper', motors[3]!)}${trans('wrist_roll', motors[2]!)}
  ${trans('shoulder_lift', motors[1]!)}${trans('shoulder_pan', motors[0]!)}
</robot>`;

function derive(urdf: string) {
  const r = deriveProfile(urdf, 'so', 'so.urdf');
  if (!r.ok) throw new Error(r.errors.join('; '));
  return r.derived as {
    json: {
      ik: { tipLink: string };
      servos: { id: string; joint: string }[];
      $import: { toolJoints: string[] };
    };
    notes: string[];
    urdf: string;
  };
}

describe('the tool rules of robot import', () => {
  test('a fixed link named like a gripper frame is the tool centre, not the moving jaw', () => {
    const d = derive(SO());
    expect(d.json.ik.tipLink).toBe('gripper_frame_link');
    expect(d.notes[0]).toMatch(/tool frame, on a fixed joint/);
    expect(d.urdf).not.toMatch(/<link name="tcp"/);
  });

  test('the jaw is a tool joint: a servo after the chain, listed as such', () => {
    const d = derive(SO());
    expect(d.json.servos.map((s) => s.joint)).toEqual([
      'shoulder_pan',
      'shoulder_lift',
      'wrist_roll',
      'gripper',
    ]);
    expect(d.json.$import.toolJoints).toEqual(['gripper']);
  });

  test('without a tool frame the tcp goes on the jaw holder, never on the jaw', () => {
    const noFrame = SO()
      .replace(/<link name="gripper_frame_link"\/>/, '')
      .replace(/<joint name="gripper_frame_joint"[\s\S]*?<\/joint>/, '');
    const d = derive(noFrame);
    expect(d.json.ik.tipLink).toBe('tcp');
    expect(d.urdf).toMatch(/<parent link="gripper_link"\/>\s*<child link="tcp"\/>/);
    expect(d.json.$import.toolJoints).toEqual(['gripper']);
  });

  test('a frame named like a tool frame on a moving joint is not taken', () => {
    const moving = SO('tool_frame').replace(
      /<joint name="gripper_frame_joint" type="fixed">/,
      '<joint name="gripper_frame_joint" type="continuous">',
    );
    expect(derive(moving).json.ik.tipLink).not.toBe('tool_frame');
  });

  test('numbered transmission actuators are the servo ids (motor1 → 001)', () => {
    expect(derive(SO()).json.servos.map((s) => s.id)).toEqual(['001', '002', '003', '004']);
    // Duplicated or unnumbered actuators: ids in order from 000.
    const dup = derive(SO('gripper_frame_link', ['motor1', 'motor1', 'motor3', 'motor4']));
    expect(dup.json.servos.map((s) => s.id)).toEqual(['000', '001', '002', '003']);
    expect(transmissionIds(SO(), ['shoulder_pan', 'elbow'])).toBeUndefined();
  });

  test('a joint moving a link named gripper is no tool joint when a driven joint follows it', () => {
    const parsed = parseUrdfJoints(SO());
    if (!parsed.ok) throw new Error(parsed.errors.join('; '));
    const renamed = parsed.joints.map((j) =>
      j.name === 'wrist_roll'
        ? { ...j, child: 'gripper' }
        : j.parent === 'gripper_link'
          ? { ...j, parent: 'gripper' }
          : j,
    );
    expect(toolJoints(renamed).map((j) => j.name)).toEqual(['gripper']);
  });
});
