/**
 * The topic names an arm's data has in Foxglove and Lichtblick: the MCAP export writes them, the
 * layout deploy/foxglove/armtwin-arm.json reads them, and the live Foxglove server (docs/foxglove.md)
 * uses the same `/{arm}/…` names, so one layout serves a recording and a live arm. The stored
 * points' own topics (servo, command, ik) are the export's alone.
 */
export const FOXGLOVE_TOPICS = {
  /** The URDF, meshes inline (std_msgs/String shape: `{"data": "<robot …>"}`). */
  robotDescription: (arm: string) => `/${arm}/robot_description`,
  /** foxglove.FrameTransforms: every URDF joint's parent → child transform. */
  transforms: (arm: string) => `/${arm}/tf`,
  /** foxglove.JointStates: the profile's joints as reported, servo order. */
  jointStates: (arm: string) => `/${arm}/joint_states`,
  /** The joints as last commanded (foxglove.JointStates shape: every joint, servo order). */
  targets: (arm: string) => `/${arm}/targets`,
  /** foxglove.Log: the control log (who took, gave, lost control; refusals). */
  log: (arm: string) => `/${arm}/log`,
  /** armtwin.ServoSample, per servo. */
  servo: (arm: string, id: string) => `/arm/${arm}/servo/${id}`,
  /** armtwin.Command, per servo. */
  command: (arm: string, id: string) => `/arm/${arm}/command/${id}`,
  /** armtwin.IkResult. */
  ik: (arm: string) => `/arm/${arm}/ik`,
} as const;
