/**
 * An imported LeRobot episode (./lerobotDataset.ts) as the History replay's record: each frame's
 * `observation.state` in LeRobot's units back to armtwin's servo angles (`degreesFromLerobot`,
 * the export's own conversion in @armtwin/robot), matched to the active robot's servos by motor
 * name (`shoulder_pan.pos` ↔ servo `shoulder_pan`), on a clock that starts at `startMs`; its
 * `action` the same way, shown beside the state (where every frame has one). The
 * replay then plays it on the sibling arm, and "Make plan from this range" turns it into a plan
 * (rehearsed in Model mode, run through the controller's limits and zones). Pure.
 */
import { degreesFromLerobot, lerobotMotorName, type ProfileServo } from '@armtwin/robot';
import type { ReplayRecord } from '../replay/ReplayPlayer.ts';
import type { DatasetEpisode } from './lerobotDataset.ts';

type Servo = Pick<ProfileServo, 'key' | 'name' | 'min' | 'max'>;

/** The record, or why the dataset's motors are not the robot's. */
export function recordFromEpisode(
  servos: readonly Servo[],
  names: readonly string[],
  episode: Omit<DatasetEpisode, 'videos'>,
  startMs: number,
): { ok: true; record: ReplayRecord } | { ok: false; error: string } {
  const columns = servos.map((s) => names.indexOf(lerobotMotorName(s)));
  const missing = servos.filter((_, i) => columns[i]! < 0).map(lerobotMotorName);
  if (missing.length > 0)
    return {
      ok: false,
      error: `the dataset has no ${missing.join(', ')} (its motors: ${names.join(', ')})`,
    };
  if (episode.timestamps.length === 0)
    return { ok: false, error: `episode ${episode.index} has no frame` };
  const times = episode.timestamps.map((t) => startMs + t * 1000);
  const toServos = (row: readonly number[]) =>
    servos.map((s, i) => degreesFromLerobot(s, row[columns[i]!]!));
  const angles = episode.state.map(toServos);
  const hasAction =
    episode.action.length === times.length &&
    episode.action.every((row) => columns.every((c) => Number.isFinite(row[c])));
  return {
    ok: true,
    record: {
      ids: servos.map((s) => s.key),
      times,
      angles,
      start: times[0]!,
      stop: Math.max(times.at(-1)!, times[0]! + 1),
      dataset: `episode ${episode.index}`,
      ...(hasAction ? { action: episode.action.map(toServos) } : {}),
    },
  };
}
