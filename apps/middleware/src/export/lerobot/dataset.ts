/**
 * A LeRobot v3.0 dataset's contents (LeRobot 0.6.1's layout, `CODEBASE_VERSION` "v3.0") from
 * resampled episodes: the frames' columns (data/chunk-000/file-000.parquet), one row per
 * episode (meta/episodes/chunk-000/file-000.parquet, with its per-episode statistics), the tasks
 * (meta/tasks.parquet), meta/stats.json and meta/info.json. Everything fits one chunk and one
 * file (LeRobot starts a new file past 100 MB, about a million SO-101 frames). Each camera's
 * video (./video.ts, written before) is a `video` feature `observation.images.<cam>` with its
 * place in the video file per episode (`videos/<key>/from_timestamp`, `to_timestamp`); its pixel
 * statistics go to meta/stats.json only (./video-stats.ts), not per episode. Pure, no I/O.
 */
import { lerobotMotorName, type Profile } from '@armtwin/robot';
import type { EpisodeFrames } from './frames.ts';
import { featureStats, STAT_NAMES, type FeatureStats } from './stats.ts';
import { VIDEO_PATH, type CameraVideo } from './video.ts';

export const CODEBASE_VERSION = 'v3.0';
export const DATA_PATH = 'data/chunk-{chunk_index:03d}/file-{file_index:03d}.parquet';
export const DATA_FILE = 'data/chunk-000/file-000.parquet';
export const EPISODES_FILE = 'meta/episodes/chunk-000/file-000.parquet';
export const TASKS_FILE = 'meta/tasks.parquet';

/** The integer columns of every frame, in LeRobot's order after the vectors. */
export const INDEX_COLUMNS = ['frame_index', 'episode_index', 'index', 'task_index'] as const;
/** Features in the order LeRobot's writer lists them. */
const VECTOR_FEATURES = ['observation.state', 'action'] as const;
const FEATURE_ORDER = [...VECTOR_FEATURES, 'timestamp', ...INDEX_COLUMNS] as const;
export type FeatureName = (typeof FEATURE_ORDER)[number];

export interface DatasetTables {
  info: Record<string, unknown>;
  stats: Record<FeatureName, FeatureStats>;
  tasks: string[];
  /** One entry per frame. */
  data: {
    'observation.state': number[][];
    action: number[][];
    timestamp: number[];
  } & Record<(typeof INDEX_COLUMNS)[number], number[]>;
  /** One row per episode: column name → value (numbers, number lists, a task list). */
  episodes: Record<string, unknown>[];
}

/** LeRobot's robot type for an armtwin profile: its SO follower for the SO-100/101. */
export function robotType(profile: Profile): string {
  return /^so10[01]$/.test(profile.name) ? `${profile.name}_follower` : profile.name;
}

/** Column-wise stats of one feature's values over `frames` (scalars become 1-vectors). */
function statsOf(data: DatasetTables['data'], from: number, to: number) {
  const out = {} as Record<FeatureName, FeatureStats>;
  for (const f of FEATURE_ORDER) {
    const col = data[f].slice(from, to) as (number | number[])[];
    out[f] = featureStats(col.map((v) => (Array.isArray(v) ? v : [v])));
  }
  return out;
}

export function buildDataset(
  profile: Profile,
  episodes: readonly EpisodeFrames[],
  fps: number,
  videos: readonly CameraVideo[] = [],
): DatasetTables {
  const tasks: string[] = [];
  const data: DatasetTables['data'] = {
    'observation.state': [],
    action: [],
    timestamp: [],
    frame_index: [],
    episode_index: [],
    index: [],
    task_index: [],
  };
  const rows: Record<string, unknown>[] = [];
  episodes.forEach((ep, e) => {
    if (ep.timestamps.length === 0)
      throw new RangeError(`episode ${e} is shorter than one frame at ${fps} fps`);
    let task = tasks.indexOf(ep.episode.task);
    if (task < 0) task = tasks.push(ep.episode.task) - 1;
    const from = data.index.length;
    ep.timestamps.forEach((t, k) => {
      // float32 on disk: the stats are of what LeRobot will read
      data['observation.state'].push(ep.state[k]!.map(Math.fround));
      data.action.push(ep.action[k]!.map(Math.fround));
      data.timestamp.push(Math.fround(t));
      data.frame_index.push(k);
      data.episode_index.push(e);
      data.index.push(from + k);
      data.task_index.push(task);
    });
    const to = data.index.length;
    const row: Record<string, unknown> = {
      episode_index: e,
      tasks: [ep.episode.task],
      length: to - from,
      'data/chunk_index': 0,
      'data/file_index': 0,
      dataset_from_index: from,
      dataset_to_index: to,
    };
    for (const v of videos) {
      row[`videos/${v.key}/chunk_index`] = 0;
      row[`videos/${v.key}/file_index`] = 0;
      row[`videos/${v.key}/from_timestamp`] = v.ranges[e]!.from;
      row[`videos/${v.key}/to_timestamp`] = v.ranges[e]!.to;
    }
    const stats = statsOf(data, from, to);
    for (const f of FEATURE_ORDER) for (const s of STAT_NAMES) row[`stats/${f}/${s}`] = stats[f][s];
    row['meta/episodes/chunk_index'] = 0;
    row['meta/episodes/file_index'] = 0;
    rows.push(row);
  });
  if (rows.length === 0) throw new RangeError('no episode to export');
  const names = profile.servos.map(lerobotMotorName);
  const vector = { dtype: 'float32', shape: [names.length], names };
  const scalar = (dtype: string) => ({ dtype, shape: [1], names: null });
  const info = {
    codebase_version: CODEBASE_VERSION,
    fps,
    features: {
      'observation.state': vector,
      action: vector,
      timestamp: scalar('float32'),
      ...Object.fromEntries(INDEX_COLUMNS.map((c) => [c, scalar('int64')])),
      ...Object.fromEntries(
        videos.map((v) => [
          v.key,
          {
            dtype: 'video',
            shape: [v.info['video.height'], v.info['video.width'], v.info['video.channels']],
            names: ['height', 'width', 'channels'],
            info: v.info,
          },
        ]),
      ),
    },
    total_episodes: rows.length,
    total_frames: data.index.length,
    total_tasks: tasks.length,
    chunks_size: 1000,
    data_files_size_in_mb: 100,
    video_files_size_in_mb: 200,
    data_path: DATA_PATH,
    video_path: videos.length > 0 ? VIDEO_PATH : null,
    robot_type: robotType(profile),
    splits: { train: `0:${rows.length}` },
  };
  return { info, stats: statsOf(data, 0, data.index.length), tasks, data, episodes: rows };
}
