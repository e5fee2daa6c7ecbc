/**
 * A LeRobot dataset folder read in the page (docs/dataset.md, "Import"): v3.0 (`meta/info.json`,
 * `meta/tasks.parquet`, `data/chunk-NNN/file-NNN.parquet`) and v2.1 (`meta/tasks.jsonl`,
 * `data/chunk-NNN/episode_NNNNNN.parquet`). The frames' Parquet is read with hyparquet (pure
 * JavaScript, the reader beside the export's hyparquet-writer): `observation.state`,
 * `action`, `timestamp`, `episode_index`, `task_index`. Video features are not read. Every
 * refusal says what is missing. No DOM: the files come as `DatasetFile`s.
 */
import { parquetReadObjects } from 'hyparquet';

export interface DatasetFile {
  /** Path inside the picked folder, `/`-separated; a leading folder name is allowed. */
  path: string;
  arrayBuffer(): Promise<ArrayBuffer>;
  text(): Promise<string>;
}

export interface DatasetEpisode {
  index: number;
  task: string;
  /** Seconds from the episode's start, one per frame. */
  timestamps: number[];
  /** One row per frame, in LeRobot's units, in `names` order. */
  state: number[][];
  action: number[][];
}

export interface LerobotDataset {
  /** The folder's name, when the files carried one. */
  name: string;
  version: string;
  fps: number;
  robotType: string;
  /** The motors of `observation.state` (`shoulder_pan.pos`, …). */
  names: string[];
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

/** Reads the folder's metadata and every episode's frames. */
export async function readLerobotDataset(files: readonly DatasetFile[]): Promise<LerobotDataset> {
  const { name, byPath } = rooted(files);
  const info = JSON.parse(await byPath.get('meta/info.json')!.text()) as {
    codebase_version?: string;
    fps?: number;
    robot_type?: string | null;
    features?: Record<string, { names?: unknown }>;
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
        ep = { index: e, task, timestamps: [], state: [], action: [] };
        episodes.set(e, ep);
      }
      const state = vector(r['observation.state'], `${path}: observation.state`);
      ep.timestamps.push(Number(r.timestamp));
      ep.state.push(state);
      ep.action.push(r.action === undefined ? state : vector(r.action, `${path}: action`));
    }
  }
  return {
    name,
    version,
    fps: Number(info.fps),
    robotType: String(info.robot_type ?? ''),
    names: names as string[],
    episodes: [...episodes.values()].sort((a, b) => a.index - b.index),
  };
}
