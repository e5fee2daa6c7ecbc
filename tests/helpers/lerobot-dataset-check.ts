/**
 * A dataset folder loaded by LeRobot's own `LeRobotDataset` (tests/helpers/lerobot/
 * dataset_check.py, in the LeRobot venv): what it reports of the dataset (episodes, frames,
 * features, cameras and their video and pixel statistics) and of each asked frame (its indices,
 * task, state, action, and each camera's picture shape and bottom rows, base64 gray).
 */
import { runLerobotScript } from './lerobot-python.ts';

export interface DatasetCheck {
  num_episodes: number;
  num_frames: number;
  fps: number;
  features: Record<string, { dtype: string; shape: number[]; names: string[] | null }>;
  robot_type: string;
  camera_keys: string[];
  video_info: Record<string, Record<string, unknown>>;
  stats_camera_mean: Record<string, number[][][]>;
  episode_lengths: number[];
  frames: {
    index: number;
    frame_index: number;
    episode_index: number;
    timestamp: number;
    task: string;
    state: number[];
    action: number[];
    images: Record<string, { shape: number[]; band: string }>;
  }[];
}

/** Loads the dataset at `root` as `repo_id`, reading frames 0..frames-1 and `band` bottom rows of each picture. */
export function checkLerobotDataset(o: {
  root: string;
  repo_id: string;
  frames: number;
  band: number;
}): DatasetCheck {
  return runLerobotScript<DatasetCheck>('dataset_check.py', {
    root: o.root,
    repo_id: o.repo_id,
    frames: Array.from({ length: o.frames }, (_, k) => k),
    band: o.band,
  });
}
