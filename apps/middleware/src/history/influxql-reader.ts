/**
 * The InfluxQL `HistoryReader`: the statements of influxql.ts POSTed to the v1 `/query` API,
 * which InfluxDB 1.8, 2.x (the bucket's DBRP mapping; 2.x makes a virtual one for every bucket)
 * and 3.x serve. Answers are read chunked (one JSON object per line), so a long export never
 * meets a server's row limit; series become rows of the shape the Flux reader gives.
 */
import {
  actualCountStatement,
  actualStatement,
  alarmsStatements,
  auditStatement,
  commandsStatements,
  measurementStatement,
  poseStatement,
  seriesStatement,
} from './influxql.ts';
import { actualFromMs } from './options.ts';
import type { HistoryReader, InfluxSource } from './reader.ts';
import { rowTime, type Row } from './shape.ts';

interface V1Series {
  name: string;
  tags?: Record<string, string>;
  columns: string[];
  values?: unknown[][];
}
interface V1Result {
  statement_id?: number;
  series?: V1Series[];
  error?: string;
}

/** The `db` and `rp` of a bucket: `db/rp` on 1.8, a bucket or database name elsewhere. */
export function dbrp(bucket: string): { db: string; rp?: string } {
  const i = bucket.indexOf('/');
  return i < 0 ? { db: bucket } : { db: bucket.slice(0, i), rp: bucket.slice(i + 1) };
}

/** One answer of `/query` (plain or chunked, one JSON object per line) → rows per statement. */
export function parseV1Answer(text: string, statements: number): Row[][] {
  const out: Row[][] = Array.from({ length: statements }, () => []);
  for (const line of text.split('\n')) {
    if (!line.trim()) continue;
    const body = JSON.parse(line) as { results?: V1Result[]; error?: string };
    if (body.error) throw new Error(body.error);
    for (const r of body.results ?? []) {
      if (r.error) throw new Error(r.error);
      const rows = out[r.statement_id ?? 0];
      if (!rows) continue;
      for (const s of r.series ?? []) {
        for (const v of s.values ?? []) {
          const row: Row = { _time: v[0], _measurement: s.name, ...s.tags };
          for (let j = 1; j < s.columns.length; j++) row[s.columns[j]!] = v[j];
          if (s.columns.length === 2) row._value = v[1];
          rows.push(row);
        }
      }
    }
  }
  return out;
}

/** Windows stamped before `fromMs` (InfluxQL's first window) start at `fromMs`, as Flux's do. */
function clipToStart(rows: Row[], fromMs: number): Row[] {
  const from = new Date(fromMs).toISOString();
  for (const r of rows) if (rowTime(r) < fromMs) r._time = from;
  return rows;
}

/** Runs InfluxQL statements in one request on `/query`; rows per statement. */
export async function queryV1(src: InfluxSource, statements: readonly string[]): Promise<Row[][]> {
  const { db, rp } = dbrp(src.bucket);
  const headers: Record<string, string> = {};
  if (src.token.includes(':') && !src.token.includes(' ')) {
    const [u, p] = src.token.split(':', 2) as [string, string];
    headers.authorization = `Basic ${Buffer.from(`${u}:${p}`).toString('base64')}`;
  } else if (src.token) headers.authorization = `Token ${src.token}`;
  const form = new URLSearchParams({ db, q: statements.join(';\n'), chunked: 'true' });
  if (rp) form.set('rp', rp);
  form.set('chunk_size', '10000');
  const res = await fetch(`${src.url.replace(/\/+$/, '')}/query`, {
    method: 'POST',
    headers,
    body: form,
    signal: AbortSignal.timeout(src.timeoutMs),
  });
  const text = await res.text();
  if (!res.ok) throw new Error(`InfluxQL query failed: ${res.status} ${text.slice(0, 300)}`);
  return parseV1Answer(text, statements.length);
}

export function influxqlReader(src: InfluxSource): HistoryReader {
  const run = (statements: string[]) => queryV1(src, statements);
  const one = async (statement: string): Promise<Row[]> => (await run([statement]))[0]!;

  return {
    language: 'influxql',
    series: async (p, every) => clipToStart(await one(seriesStatement(p, every)), p.startMs),
    pose: async (p, every) => clipToStart(await one(poseStatement(p, every)), p.startMs),
    async alarms(p, max) {
      const [tempOn, tempEnd, voltOn, voltEnd] = await run(alarmsStatements(p, max));
      const tag = (rows: Row[], field: string, ends: boolean) =>
        rows.map((r) => ({ ...r, _field: field, _value: ends ? NaN : r[field] }));
      return [
        ...tag(tempOn!, 'temp', false),
        ...tag(tempEnd!, 'temp', true),
        ...tag(voltOn!, 'volt', false),
        ...tag(voltEnd!, 'volt', true),
      ];
    },
    async commands(p, lookback, max) {
      const [before, during] = await run(commandsStatements(p, lookback, max));
      return [...before!, ...during!];
    },
    actualCount: (p) => one(actualCountStatement(p)),
    async actual(p, every) {
      const rows = await one(actualStatement(p, every));
      return every === null ? rows : clipToStart(rows, actualFromMs(p.startMs));
    },
    audit: (p, max) => one(auditStatement(p, max)),
    measurement: (m, arm, a, b) => one(measurementStatement(m, arm, a, b)),
  };
}
