/**
 * `armtwin export --format lerobot`: which episodes (the marked ones, `--episodes`, or one
 * `--from`/`--to` range with `--task`) and the export itself (@armtwin/middleware/export/lerobot).
 */
import type { HistoryReader } from '@armtwin/middleware';
import { loadRecordingRobot } from '@armtwin/middleware/export';
import { exportLerobot, type Episode } from '@armtwin/middleware/export/lerobot';
import { keptEpisodes, readMarks } from '@armtwin/middleware/episodes';

export interface LerobotFlags {
  arm: string;
  out: string;
  fps: number;
  profile?: string;
  models?: string;
  task?: string;
  episodes?: string;
  /** The camera recordings' folder. */
  cameras?: string;
  /** Only these cameras, comma-separated. */
  camera?: string;
}

/** `all`, or 0-based positions among the kept episodes in range, `0,2,3`. */
export function parseEpisodeList(value: string): 'all' | number[] {
  if (value === 'all') return 'all';
  const list = value.split(',').map((v) => Number(v.trim()));
  if (list.length === 0 || list.some((n) => !Number.isInteger(n) || n < 0))
    throw new Error(`--episodes is "all" or episode numbers such as 0,2 (got "${value}")`);
  return list;
}

/** The episodes to export; throws saying what is missing. */
async function chosen(
  reader: HistoryReader,
  f: LerobotFlags,
  range: { startMs?: number; stopMs?: number },
): Promise<Episode[]> {
  if (f.episodes === undefined) {
    if (range.startMs === undefined || range.stopMs === undefined)
      throw new Error('--format lerobot needs --episodes, or --from and --to');
    const task = f.task?.trim();
    if (!task)
      throw new Error("--format lerobot needs --task (the episode's task) with --from/--to");
    return [{ startMs: range.startMs, stopMs: range.stopMs, task }];
  }
  const which = parseEpisodeList(f.episodes);
  const kept = keptEpisodes(await readMarks(reader, f.arm), range.startMs, range.stopMs);
  if (kept.length === 0) throw new Error(`arm ${f.arm} has no stopped, kept episode in range`);
  const picked = which === 'all' ? kept : which.map((n) => kept[n]);
  const missing = which === 'all' ? [] : which.filter((n) => !kept[n]);
  if (missing.length > 0)
    throw new Error(
      `no episode ${missing.join(', ')}: arm ${f.arm} has ${kept.length} (0–${kept.length - 1})`,
    );
  return picked.map((m) => ({
    startMs: m!.startMs,
    stopMs: m!.stopMs!,
    task: f.task?.trim() || m!.task,
  }));
}

/** Writes the dataset; the line to print. */
export async function runLerobotExport(
  reader: HistoryReader,
  f: LerobotFlags,
  range: { startMs?: number; stopMs?: number },
): Promise<string> {
  if (!f.profile) throw new Error('--format lerobot needs --profile (motors and units)');
  const { profile } = loadRecordingRobot(f.profile, f.models);
  const episodes = await chosen(reader, f, range);
  const s = await exportLerobot({
    reader,
    arm: f.arm,
    profile,
    episodes,
    fps: f.fps,
    out: f.out,
    ...(f.cameras ? { camerasDir: f.cameras } : {}),
    ...(f.camera ? { cameras: f.camera.split(',').map((c) => c.trim()) } : {}),
  });
  const cameras = s.cameras.length > 0 ? `video: ${s.cameras.join(', ')}` : 'no camera';
  const skipped = s.skipped.length > 0 ? `; left out: ${s.skipped.join(', ')}` : '';
  return `${f.out}: LeRobot v3.0 dataset, ${s.episodes} episode(s), ${s.frames} frames at ${f.fps} fps, ${s.tasks} task(s), ${cameras}${skipped}`;
}
