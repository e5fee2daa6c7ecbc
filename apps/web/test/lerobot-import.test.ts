/**
 * The HUD's LeRobot import (core/dataset): a dataset that `armtwin export --format lerobot`
 * writes (buildDataset + writeParquetFiles, the export's own code) reads back to the same
 * servo angles, in its v3.0 layout and rearranged as v2.1 (per-episode files, tasks.jsonl);
 * the unit conversion is the export's, inverted; what is not a usable dataset is refused,
 * saying why. (LeRobot's own writer is in tests/e2e/dataset-import.spec.ts.)
 */
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { degreesFromLerobot, lerobotValue, type Profile } from '@armtwin/robot';
import { buildDataset, type EpisodeFrames } from '../../middleware/src/export/lerobot/index.ts';
import { writeParquetFiles } from '../../middleware/src/export/lerobot/parquet.ts';
import { readLerobotDataset, type DatasetFile } from '../src/core/dataset/lerobotDataset.ts';
import { recordFromEpisode } from '../src/core/dataset/episodeRecord.ts';
import { loadProfile } from '../../../tests/e2e/support/profiled-arm.ts';

const SO101: Profile = loadProfile('so101');
const dirs: string[] = [];
afterAll(() => dirs.forEach((d) => fs.rmSync(d, { recursive: true, force: true })));

/** Servo degrees of episode e, frame k (within the SO-101's limits). */
const degrees = (e: number, k: number) =>
  SO101.servos.map((s, i) => Math.max(s.min, Math.min(s.max, (e + 1) * (k - 3) * (i + 1))));

function frames(e: number, n: number, task: string): EpisodeFrames {
  const ts = Array.from({ length: n }, (_, k) => k / 30);
  const state = ts.map((_, k) => SO101.servos.map((s, i) => lerobotValue(s, degrees(e, k)[i]!)));
  return { episode: { startMs: 0, stopMs: n * 34, task }, timestamps: ts, state, action: state };
}

/** The export's files in a new folder named `name`; returns them as the page would get them. */
function exported(name: string): { root: string; files: () => DatasetFile[] } {
  const top = fs.mkdtempSync(path.join(os.tmpdir(), 'armtwin-import-unit-'));
  dirs.push(top);
  const root = path.join(top, name);
  const t = buildDataset(SO101, [frames(0, 7, 'pick'), frames(1, 5, 'place')], 30);
  fs.mkdirSync(path.join(root, 'meta'), { recursive: true });
  writeParquetFiles(root, t);
  fs.writeFileSync(path.join(root, 'meta/info.json'), JSON.stringify(t.info));
  const files = () =>
    (fs.readdirSync(root, { recursive: true }) as string[])
      .filter((p) => fs.statSync(path.join(root, p)).isFile())
      .map((p) => ({
        path: `${name}/${p.split(path.sep).join('/')}`,
        arrayBuffer: async () => {
          const b = fs.readFileSync(path.join(root, p));
          return b.buffer.slice(b.byteOffset, b.byteOffset + b.byteLength) as ArrayBuffer;
        },
        text: async () => fs.readFileSync(path.join(root, p), 'utf8'),
      }));
  return { root, files };
}

describe('LeRobot units', () => {
  test("the import's conversion undoes the export's (gripper 0–100 % of its range)", () => {
    const gripper = SO101.servos.find((s) => s.name === 'gripper')!;
    expect(lerobotValue(gripper, gripper.max)).toBe(100);
    expect(degreesFromLerobot(gripper, 0)).toBe(gripper.min);
    for (const s of SO101.servos)
      expect(degreesFromLerobot(s, lerobotValue(s, 12.5))).toBeCloseTo(12.5, 9);
  });
});

describe('reading a dataset folder', () => {
  test('v3.0 as exported: episodes, tasks and the servo angles come back', async () => {
    const d = await readLerobotDataset(exported('so101-demo').files());
    expect(d).toMatchObject({ name: 'so101-demo', version: 'v3.0', fps: 30 });
    expect(d.robotType).toBe('so101_follower');
    expect(d.episodes.map((e) => [e.index, e.task, e.timestamps.length])).toEqual([
      [0, 'pick', 7],
      [1, 'place', 5],
    ]);
    const r = recordFromEpisode(SO101.servos, d.names, d.episodes[1]!, 1000);
    if (!r.ok) throw new Error(r.error);
    expect(r.record.ids).toEqual(['001', '002', '003', '004', '005', '006']);
    expect(r.record.start).toBe(1000);
    expect(r.record.times[3]).toBeCloseTo(1100, 3);
    r.record.angles.forEach((row, k) =>
      row.forEach((a, i) => expect(a).toBeCloseTo(degrees(1, k)[i]!, 3)),
    );
  });

  test('v2.1: per-episode data files, meta/tasks.jsonl and one video per episode', async () => {
    const { root, files } = exported('old');
    const info = JSON.parse(fs.readFileSync(path.join(root, 'meta/info.json'), 'utf8'));
    const key = 'observation.images.wrist';
    fs.writeFileSync(
      path.join(root, 'meta/info.json'),
      JSON.stringify({
        ...info,
        codebase_version: 'v2.1',
        video_path: 'videos/chunk-{episode_chunk:03d}/{video_key}/episode_{episode_index:06d}.mp4',
        features: { ...info.features, [key]: { dtype: 'video', shape: [48, 64, 3] } },
      }),
    );
    // Episode 1's video only: episode 0's is missing from the folder.
    fs.mkdirSync(path.join(root, 'videos/chunk-000', key), { recursive: true });
    fs.writeFileSync(path.join(root, 'videos/chunk-000', key, 'episode_000001.mp4'), 'mp4');
    fs.renameSync(
      path.join(root, 'data/chunk-000/file-000.parquet'),
      path.join(root, 'data/chunk-000/episode_000000.parquet'),
    );
    fs.rmSync(path.join(root, 'meta/tasks.parquet'));
    fs.writeFileSync(
      path.join(root, 'meta/tasks.jsonl'),
      '{"task_index": 0, "task": "pick"}\n{"task_index": 1, "task": "place"}\n',
    );
    const d = await readLerobotDataset(files());
    expect(d.version).toBe('v2.1');
    expect(d.episodes.map((e) => [e.task, e.state.length])).toEqual([
      ['pick', 7],
      ['place', 5],
    ]);
    expect(d.videoKeys).toEqual([key]);
    const [first, second] = d.episodes.map((e) => e.videos[0]!);
    expect(first).toMatchObject({ file: null });
    expect(second!.clip).toEqual({
      key,
      path: `videos/chunk-000/${key}/episode_000001.mp4`,
      fromS: 0,
      toS: 5 / 30,
    });
    expect(await second!.file!.text()).toBe('mp4');
  });

  test('what is not a usable dataset is refused, saying why', async () => {
    await expect(readLerobotDataset([])).rejects.toThrow('no meta/info.json');
    const { root, files } = exported('new');
    const info = JSON.parse(fs.readFileSync(path.join(root, 'meta/info.json'), 'utf8'));
    fs.writeFileSync(
      path.join(root, 'meta/info.json'),
      JSON.stringify({ ...info, codebase_version: 'v2.0' }),
    );
    await expect(readLerobotDataset(files())).rejects.toThrow(
      'LeRobot dataset v2.0: armtwin reads v3.0 and v2.1',
    );
    const d = { index: 0, task: 't', timestamps: [0], state: [[1, 2]], action: [[1, 2]] };
    expect(recordFromEpisode(SO101.servos, ['shoulder_pan.pos', 'x.pos'], d, 0)).toEqual({
      ok: false,
      error: expect.stringMatching(
        /^the dataset has no shoulder_lift\.pos, .*gripper\.pos \(its motors: shoulder_pan\.pos, x\.pos\)$/,
      ),
    });
  });
});
