/**
 * The URDF reader's skipping rules: only `<robot>`'s own `<link>` and `<joint>` children
 * describe the robot; the `<joint>`s that `<ros2_control>`, `<transmission>` and `<gazebo>`
 * blocks name, commented-out joints and CDATA are not joints; text that is not well-formed XML
 * is refused with the parser's reason; mesh paths are found and rewritten in links only.
 */
import { describe, expect, it } from 'vitest';
import { meshRefs, parseUrdfJoints, planImport, rewriteMeshPaths } from '../src/index.ts';

const ARM = `<?xml version="1.0"?>
<robot name="two" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <!-- <joint name="old" type="revolute"><parent link="base"/><child link="l1"/></joint> -->
  <ros2_control name="hw" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="j1">
      <command_interface name="position"><param name="min">-1</param></command_interface>
      <state_interface name="position"/>
    </joint>
    <joint name="j2"><state_interface name="position"/></joint>
  </ros2_control>
  <link name="base"><visual><geometry><mesh filename="package://arm/base.stl"/></geometry></visual></link>
  <link name="l1">
    <visual><geometry><mesh filename="l1.dae"/></geometry></visual>
    <collision><geometry><mesh filename="l1_collision.stl"/></geometry></collision>
  </link>
  <link name="l2"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" velocity="2" effort="1"/>
  </joint>
  <joint name="j2" type="continuous">
    <parent link="l1"/><child link="l2"/><axis xyz="0 1 0"/>
  </joint>
  <transmission name="t1">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="j1"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <gazebo reference="l1"><material>Gazebo/Grey</material><mesh filename="gazebo_only.stl"/></gazebo>
  <gazebo><plugin name="p" filename="libgazebo_ros2_control.so"><joint name="j9"/></plugin></gazebo>
  <description><![CDATA[ <joint name="j8" type="fixed"/> ]]></description>
</robot>
`;

describe('parseUrdfJoints', () => {
  it("reads the robot's own joints and links and skips ros2_control, transmission, gazebo, comments and CDATA", () => {
    const r = parseUrdfJoints(ARM);
    if (!r.ok) throw new Error(r.errors.join('; '));
    expect(r.robot).toBe('two');
    expect(r.links).toEqual(['base', 'l1', 'l2']);
    expect(r.joints.map((j) => j.name)).toEqual(['j1', 'j2']);
    expect(r.joints[0]).toMatchObject({
      type: 'revolute',
      parent: 'base',
      child: 'l1',
      xyz: [0, 0, 0.1],
      rpy: [0, 0, 0],
      axis: [0, 0, 1],
      lower: -1,
      upper: 1,
      velocity: 2,
    });
    expect(r.joints[1]).toMatchObject({ type: 'continuous', xyz: [0, 0, 0], axis: [0, 1, 0] });
  });

  it('still refuses a real joint with no parent, naming it', () => {
    const bad = ARM.replace('<parent link="l1"/><child link="l2"/>', '<child link="l2"/>');
    expect(parseUrdfJoints(bad)).toEqual({
      ok: false,
      errors: ['joint "j2" has no <parent link>'],
    });
  });

  it('refuses text that is not well-formed XML, with the reason', () => {
    const r = parseUrdfJoints(ARM.replace('</transmission>', ''));
    expect(r.ok).toBe(false);
    if (r.ok) return;
    expect(r.errors[0]).toMatch(/^not well-formed XML: .*transmission/);
  });

  it('refuses a document whose root is not <robot>', () => {
    expect(parseUrdfJoints('<?xml version="1.0"?><sdf><model/></sdf>')).toEqual({
      ok: false,
      errors: ['no <robot> element'],
    });
  });

  it('a joint nested anywhere but under <robot> is not a joint', () => {
    const r = parseUrdfJoints(
      '<robot name="r"><link name="a"/><group><joint name="x" type="fixed"><parent link="a"/><child link="b"/></joint></group></robot>',
    );
    expect(r).toEqual({ ok: false, errors: ['no <joint> elements'] });
  });
});

describe('mesh references', () => {
  it("are the links' visual and collision meshes, not a gazebo block's", () => {
    expect(meshRefs(ARM)).toEqual([
      { filename: 'package://arm/base.stl', visual: true, link: 'base' },
      { filename: 'l1.dae', visual: true, link: 'l1' },
      { filename: 'l1_collision.stl', visual: false, link: 'l1' },
    ]);
  });

  it('are rewritten in place, and the rewritten URDF reads the same joints', () => {
    const out = rewriteMeshPaths(ARM, (f) => (f === 'l1.dae' ? 'meshes/l1.dae' : null));
    expect(meshRefs(out).map((m) => m.filename)).toEqual([
      'package://arm/base.stl',
      'meshes/l1.dae',
      'l1_collision.stl',
    ]);
    expect(out).toContain('<mesh filename="gazebo_only.stl"/>');
    expect(out).toContain('<ros2_control name="hw" type="system">');
    expect(parseUrdfJoints(out)).toEqual(parseUrdfJoints(ARM));
  });

  it('leave the text as it was when nothing is renamed', () => {
    expect(rewriteMeshPaths(ARM, () => null)).toBe(ARM);
  });
});

describe('planImport', () => {
  it('names the robot from the <robot> element, not from a commented-out one', () => {
    const urdf =
      '<?xml version="1.0"?>\n<!-- was: <robot name="Old Arm"> -->\n<robot name="New Arm">' +
      '<link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/>' +
      '<child link="b"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1"/></joint></robot>';
    const r = planImport({
      urdfPath: 'arm.urdf',
      urdfText: urdf,
      has: () => false,
      read: () => new Uint8Array(),
    });
    if (!r.ok) throw new Error(r.errors.join('; '));
    expect(r.plan.name).toBe('new_arm');
  });
});
