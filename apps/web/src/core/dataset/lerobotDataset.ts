/**
 * A LeRobot dataset folder read in the page (docs/dataset.md, "Import"): v3.0 (`meta/info.json`,
 * `meta/tasks.parquet`, `data/chunk-NNN/file-NNN.parquet`) and v2.1 (`meta/tasks.jsonl`,
 * `data/chunk-NNN/episode_NNNNNN.parquet`). The frames' Parquet is read with hyparquet (pure
 * JavaScript, the reader beside the export's hyparquet-writer): `observation.state`,
 * `action`, `timestamp`, `episode_index`, `task_index`. Each video feature
 * (`observation.images.<cam>`) gives every episode its clip: which MP4 of the folder, and where
 * in it (./episodeVideo.ts; v3.0 from meta/episodes). Every refusal says what is missing. No
 * DOM: the files come as `DatasetFile`s.
 */
import { parquetReadObjects } from 'hyparquet';
import {
  v21Clip,
  v3Clip,
  v3Columns,
  videoCodec,
  videoKeys,
  type EpisodeClip,
  type VideoInfo,
} from './episodeVideo.ts';

export interface DatasetFile {
  /** Path inside the picked folder, `/`-separated; a leading folder name is allowed. */
  path: string;
  arrayBuffer(): Promise<ArrayBuffer>;
  text(): Promise<string>;
  /** The file itself where it is one (a picked File): played without a copy. */
  blob?(): Blob;
}

/** One camera of an episode: its clip (or why there is none) and the folder's MP4. */
export interface EpisodeVideo {
  key: string;
  clip: EpisodeClip | string;
  /** Null where the folder lacks the clip's file. */
  file: DatasetFile | null;
  /** The codec info.json names for it (`av1`, `h264`…), or null. */
  codec: string | null;
}

export interface DatasetEpisode {
  index: number;
  task: string;
  /** Seconds from the episode's start, one per frame. */
  timestamps: number[];
  /** One row per frame, in LeRobot's units, in `names` order. */
  state: number[][];
  action: number[][];
  /** One per video feature of the dataset. */
  videos: EpisodeVideo[];
}

export interface LerobotDataset {
  /** The folder's name, when the files carried one. */
  name: string;
  version: string;
  fps: number;
  robotType: string;
  /** The motors of `observation.state` (`shoulder_pan.pos`, …). */
  names: string[];
  /** Its video features, `observation.images.<cam>`. */
  videoKeys: string[];
  episodes: DatasetEpisode[];
}

export const SUPPORTED_VERSIONS = ['v3.0', 'v2.1'] as const;
const COLUMNS = ['observation.state', 'action', 'timestamp', 'episode_index', 'task_index'];

/** Files keyed by their path from the dataset's root (the folder holding meta/info.json). */
function rooted(files: readonly DatasetFile[]): { name: string; byPath: Map<string, DatasetFile> } {
  const info = files.find((f) => /(^|\/)meta\/info\.json$/.test(f.path));
  if (!info) throw new Error('not a LeRobot dataset: no meta/info.json in the folder');
  const prefix = info.path.slice(0, -'meta/info.json'.length);
  const byPath = new Map<string, DatasetFile>();
  for (const f of files) if (f.path.startsWith(prefix)) byPath.set(f.path.slice(prefix.length), f);
  return { name: prefix.replace(/\/$/, '').split('/').at(-1) ?? '', byPath };
}

const num = (v: unknown): number => (typeof v === 'bigint' ? Number(v) : Number(v));

async function readTasks(byPath: Map<string, DatasetFile>): Promise<Map<number, string>> {
  const out = new Map<number, string>();
  const parquet = byPath.get('meta/tasks.parquet');
  if (parquet) {
    const rows = await parquetReadObjects({ file: await parquet.arrayBuffer() });
    for (const r of rows) out.set(num(r.task_index), String(r.task ?? r.__index_level_0__ ?? ''));
    return out;
  }
  const jsonl = byPath.get('meta/tasks.jsonl');
  if (!jsonl) throw new Error('no meta/tasks.parquet (v3.0) or meta/tasks.jsonl (v2.1)');
  for (const line of (await jsonl.text()).split('\n')) {
    if (!line.trim()) continue;
    const r = JSON.parse(line) as { task_index: number; task: string };
    out.set(r.task_index, r.task);
  }
  return out;
}

const vector = (v: unknown, what: string): number[] => {
  if (!Array.isArray(v)) throw new Error(`${what} is not a list of numbers`);
  return v.map(Number);
};

/** v3.0: each episode's meta/episodes row (the video columns only), by episode index. */
async function readEpisodeRows(
  byPath: Map<string, DatasetFile>,
  keys: readonly string[],
): Promise<Map<number, Record<string, unknown>>> {
  const out = new Map<number, Record<string, unknown>>();
  if (keys.length === 0) return out;
  const paths = [...byPath.keys()].filter((p) => /^meta\/episodes\/.+\.parquet$/.test(p)).sort();
  for (const path of paths) {
    const rows = await parquetReadObjects({
      file: await byPath.get(path)!.arrayBuffer(),
      columns: ['episode_index', ...keys.flatMap(v3Columns)],
    });
    for (const r of rows) out.set(num(r.episode_index), r);
  }
  return out;
}

/** The episode's clip of every video feature, with the folder's file for it. */
function episodeVideos(
  info: VideoInfo & { codebase_version?: string },
  keys: readonly string[],
  ep: DatasetEpisode,
  rows: Map<number, Record<string, unknown>>,
  byPath: Map<string, DatasetFile>,
): EpisodeVideo[] {
  return keys.map((key) => {
    const clip =
      info.codebase_version === 'v2.1'
        ? v21Clip(info, key, ep.index, ep.timestamps.length)
        : v3Clip(info, key, rows.get(ep.index) ?? { episode_index: ep.index });
    const file = typeof clip === 'string' ? null : (byPath.get(clip.path) ?? null);
    return { key, clip, file, codec: videoCodec(info, key) };
  });
}

/** Reads the folder's metadata and every episode's frames. */
export async function readLerobotDataset(files: readonly DatasetFile[]): Promise<LerobotDataset> {
  const { name, byPath } = rooted(files);
  const info = JSON.parse(await byPath.get('meta/info.json')!.text()) as VideoInfo & {
    codebase_version?: string;
    fps?: number;
    robot_type?: string | null;
    features?: Record<
      string,
      { names?: unknown; dtype?: string; info?: Record<string, unknown> | null }
    >;
  };
  const version = String(info.codebase_version ?? '');
  if (!(SUPPORTED_VERSIONS as readonly string[]).includes(version))
    throw new Error(
      `LeRobot dataset ${version || 'without codebase_version'}: armtwin reads ${SUPPORTED_VERSIONS.join(' and ')}`,
    );
  const names = info.features?.['observation.state']?.names;
  if (!Array.isArray(names) || names.some((n) => typeof n !== 'string'))
    throw new Error('meta/info.json has no observation.state feature with motor names');
  const tasks = await readTasks(byPath);
  const data = [...byPath.keys()].filter((p) => /^data\/.+\.parquet$/.test(p)).sort();
  if (data.length === 0) throw new Error('no data/…/….parquet frames in the dataset');
  const episodes = new Map<number, DatasetEpisode>();
  for (const path of data) {
    const rows = await parquetReadObjects({
      file: await byPath.get(path)!.arrayBuffer(),
      columns: COLUMNS,
    });
    for (const r of rows) {
      const e = num(r.episode_index);
      let ep = episodes.get(e);
      if (!ep) {
        const task = tasks.get(num(r.task_index)) ?? '';
        ep = { index: e, task, timestamps: [], state: [], action: [], videos: [] };
        episodes.set(e, ep);
      }
      const state = vector(r['observation.state'], `${path}: observation.state`);
      ep.timestamps.push(Number(r.timestamp));
      ep.state.push(state);
      ep.action.push(r.action === undefined ? state : vector(r.action, `${path}: action`));
    }
  }
  const keys = videoKeys(info);
  const rows = version === 'v2.1' ? new Map() : await readEpisodeRows(byPath, keys);
  for (const ep of episodes.values()) ep.videos = episodeVideos(info, keys, ep, rows, byPath);
  return {
    name,
    version,
    fps: Number(info.fps),
    robotType: String(info.robot_type ?? ''),
    names: names as string[],
    videoKeys: keys,
    episodes: [...episodes.values()].sort((a, b) => a.index - b.index),
  };
}
