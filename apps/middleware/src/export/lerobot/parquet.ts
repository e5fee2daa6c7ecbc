/**
 * The dataset's three Parquet files, written with hyparquet-writer (pure JavaScript, no native
 * or Python step for `armtwin export`), with the column types LeRobot's own writer gives them:
 * float32 vectors, int64 indices, float64 statistics, lists as Parquet's LIST. meta/tasks.parquet
 * carries the pandas index metadata that `pd.read_parquet` needs to make the task text the
 * index, as LeRobot reads it (`tasks.iloc[i].name`).
 */
import fs from 'node:fs';
import path from 'node:path';
import { parquetWriteBuffer } from 'hyparquet-writer';
import { DATA_FILE, EPISODES_FILE, TASKS_FILE, type DatasetTables } from './dataset.ts';

type SchemaElement = NonNullable<Parameters<typeof parquetWriteBuffer>[0]['schema']>[number];
type Leaf = 'FLOAT' | 'DOUBLE' | 'INT64' | 'STRING';
type Kind = Leaf | { list: Leaf };
interface Column {
  name: string;
  kind: Kind;
  data: unknown[];
}

function leafElement(name: string, leaf: Leaf): SchemaElement {
  return leaf === 'STRING'
    ? { name, type: 'BYTE_ARRAY', converted_type: 'UTF8', repetition_type: 'OPTIONAL' }
    : { name, type: leaf, repetition_type: 'OPTIONAL' };
}

function schemaOf(columns: readonly Column[]): SchemaElement[] {
  const out: SchemaElement[] = [{ name: 'root', num_children: columns.length }];
  for (const c of columns) {
    if (typeof c.kind === 'string') out.push(leafElement(c.name, c.kind));
    else
      out.push(
        { name: c.name, repetition_type: 'OPTIONAL', num_children: 1, converted_type: 'LIST' },
        { name: 'list', repetition_type: 'REPEATED', num_children: 1 },
        leafElement('element', c.kind.list),
      );
  }
  return out;
}

const int64 = (v: unknown): unknown =>
  Array.isArray(v) ? v.map(int64) : typeof v === 'number' ? BigInt(v) : v;

function write(file: string, columns: Column[], kv: Record<string, string> = {}): void {
  const buffer = parquetWriteBuffer({
    columnData: columns.map((c) => {
      const leaf = typeof c.kind === 'string' ? c.kind : c.kind.list;
      return { name: c.name, data: leaf === 'INT64' ? c.data.map(int64) : c.data };
    }),
    schema: schemaOf(columns),
    kvMetadata: Object.entries(kv).map(([key, value]) => ({ key, value })),
    createdBy: 'armtwin export (hyparquet-writer)',
  });
  fs.mkdirSync(path.dirname(file), { recursive: true });
  fs.writeFileSync(file, new Uint8Array(buffer));
}

/** Column kind of an episodes-table value: by name (counts and indices are int64, times float64). */
function episodeKind(name: string, value: unknown): Kind {
  if (name === 'tasks') return { list: 'STRING' };
  if (name.endsWith('_timestamp')) return 'DOUBLE'; // a video's from/to, s
  if (Array.isArray(value)) return { list: name.endsWith('/count') ? 'INT64' : 'DOUBLE' };
  return 'INT64';
}

/** pandas' metadata for a frame whose index is the string column `index`. */
function pandasIndexMetadata(index: string, columns: Record<string, 'int64'>): string {
  const col = (name: string, pandasType: string, numpyType: string) => ({
    name,
    field_name: name,
    pandas_type: pandasType,
    numpy_type: numpyType,
    metadata: null,
  });
  return JSON.stringify({
    index_columns: [index],
    column_indexes: [
      {
        name: null,
        field_name: null,
        pandas_type: 'unicode',
        numpy_type: 'object',
        metadata: { encoding: 'UTF-8' },
      },
    ],
    columns: [
      ...Object.entries(columns).map(([n, t]) => col(n, t, t)),
      col(index, 'unicode', 'object'),
    ],
    creator: { library: 'armtwin' },
    pandas_version: '2.2.3',
  });
}

export function writeParquetFiles(root: string, t: DatasetTables): void {
  const d = t.data;
  write(path.join(root, DATA_FILE), [
    { name: 'observation.state', kind: { list: 'FLOAT' }, data: d['observation.state'] },
    { name: 'action', kind: { list: 'FLOAT' }, data: d.action },
    { name: 'timestamp', kind: 'FLOAT', data: d.timestamp },
    { name: 'frame_index', kind: 'INT64', data: d.frame_index },
    { name: 'episode_index', kind: 'INT64', data: d.episode_index },
    { name: 'index', kind: 'INT64', data: d.index },
    { name: 'task_index', kind: 'INT64', data: d.task_index },
  ]);
  const names = Object.keys(t.episodes[0]!);
  write(
    path.join(root, EPISODES_FILE),
    names.map((name) => ({
      name,
      kind: episodeKind(name, t.episodes[0]![name]),
      data: t.episodes.map((row) => row[name]),
    })),
  );
  write(
    path.join(root, TASKS_FILE),
    [
      { name: 'task_index', kind: 'INT64', data: t.tasks.map((_, i) => i) },
      { name: 'task', kind: 'STRING', data: t.tasks },
    ],
    { pandas: pandasIndexMetadata('task', { task_index: 'int64' }) },
  );
}
