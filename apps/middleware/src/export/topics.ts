/**
 * The topic names an MCAP export writes: an arm's data as Foxglove and Lichtblick read it has the
 * live server's names and schemas, from their one home (@armtwin/foxglove/topics), so one
 * layout (deploy/foxglove/armtwin-arm.json) serves a recording and a live arm. The stored points'
 * own topics (servo, command, ik) are the export's alone.
 */
import { FOXGLOVE_TOPICS as LIVE } from '@armtwin/foxglove/topics';

export const FOXGLOVE_TOPICS = {
  ...LIVE,
  /** armtwin.ServoSample, per servo. */
  servo: (arm: string, id: string) => `/arm/${arm}/servo/${id}`,
  /** armtwin.Command, per servo. */
  command: (arm: string, id: string) => `/arm/${arm}/command/${id}`,
  /** armtwin.IkResult. */
  ik: (arm: string) => `/arm/${arm}/ik`,
} as const;
