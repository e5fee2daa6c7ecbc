/**
 * The topic names an arm's data has in Foxglove and Lichtblick: the MCAP export writes them and
 * the layout deploy/foxglove/armtwin-arm.json reads them (docs/foxglove-mcap.md). One arm per
 * file: the robot description and the transforms keep ROS's names, which the 3D panel looks
 * for by itself; the rest is under the arm's id.
 */
export const FOXGLOVE_TOPICS = {
  /** The URDF, meshes inline (std_msgs/String shape: `{"data": "<robot …>"}`). */
  robotDescription: '/robot_description',
  /** foxglove.FrameTransforms: every URDF joint's parent → child transform. */
  transforms: '/tf',
  /** foxglove.JointStates: the profile's joints as reported, servo order. */
  jointStates: (arm: string) => `/arm/${arm}/joint_states`,
  /** foxglove.JointStates: the joints as last commanded, same order and units. */
  jointTargets: (arm: string) => `/arm/${arm}/joint_targets`,
  /** foxglove.Log: the control log (who took, gave, lost control; refusals). */
  log: (arm: string) => `/arm/${arm}/audit`,
  /** armtwin.ServoSample, per servo. */
  servo: (arm: string, id: string) => `/arm/${arm}/servo/${id}`,
  /** armtwin.Command, per servo. */
  command: (arm: string, id: string) => `/arm/${arm}/command/${id}`,
  /** armtwin.IkResult. */
  ik: (arm: string) => `/arm/${arm}/ik`,
} as const;
