/**
 * The LeRobot export's pure parts: resampling onto the dataset's clock (sample-and-hold, the
 * SO follower's units, actions held between commands), the frame count, and the statistics.
 */
import { describe, expect, test } from 'vitest';
import { loadRecordingRobot } from '../src/export/index.ts';
import { buildDataset, featureStats, frameCount, resample } from '../src/export/lerobot/index.ts';
import type { CommandRow, ServoRow } from '../src/export/recording.ts';

const { profile } = loadRecordingRobot('so101');
const T = Date.UTC(2026, 10, 27, 8, 0, 0);
const ns = (ms: number) => BigInt(Math.round(ms * 1000)) * 1000n;
const id = (n: number) => `00${n}`;

/** Every servo reports `deg(k, servo)` every 20 ms from T. */
function reports(count: number, deg: (k: number, servo: number) => number): ServoRow[] {
  const out: ServoRow[] = [];
  for (let k = 0; k < count; k++)
    for (let s = 1; s <= 6; s++) out.push({ ns: ns(T + 20 * k), id: id(s), angle: deg(k, s) });
  return out;
}

describe('resample', () => {
  test('each frame holds the last report at or before its tick, none after', () => {
    const [ep] = resample(
      profile,
      reports(100, (k) => k),
      [],
      [{ startMs: T + 10, stopMs: T + 1010, task: 'x' }],
      30,
    );
    expect(ep!.timestamps.length).toBe(30);
    // tick k at T + 10 + k·33.3 ms; the report at or before it is number floor((10 + k·33.3) / 20)
    ep!.state.forEach((row, k) => expect(row[0]).toBe(Math.floor((10 + (k * 1000) / 30) / 20)));
    // a report exactly on a tick counts: at 50 fps from T every tick is a report's time
    const [exact] = resample(
      profile,
      reports(100, (k) => k),
      [],
      [{ startMs: T, stopMs: T + 200, task: 'x' }],
      50,
    );
    expect(exact!.state.map((r) => r[0])).toEqual([0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
  });

  test('SO follower units: joints in degrees, the gripper in 0–100 % of its limits', () => {
    const [ep] = resample(
      profile,
      reports(5, (_, s) => (s === 6 ? 45 : -12.5)),
      [],
      [{ startMs: T, stopMs: T + 100, task: 'x' }],
      10,
    );
    expect(ep!.state[0]).toEqual([-12.5, -12.5, -12.5, -12.5, -12.5, 50]); // gripper −10..100 °
  });

  test('actions hold the last command; before the first, the reported state', () => {
    const command: CommandRow[] = [
      { ns: ns(T + 500), id: id(1), angle: 30, ms: 800 },
      { ns: ns(T + 500), id: id(6), pwm: 1500, ms: 800 },
    ];
    const [ep] = resample(
      profile,
      reports(100, () => 5),
      command,
      [{ startMs: T, stopMs: T + 1000, task: 'x' }],
      10,
    );
    expect(ep!.action[4]).toEqual([5, 5, 5, 5, 5, ((5 + 10) / 110) * 100]);
    expect(ep!.action[5]).toEqual([30, 5, 5, 5, 5, (10 / 110) * 100]); // pwm 1500 = 0°
    expect(ep!.action[9]![0]).toBe(30);
  });

  test('a servo with no report before the first tick is named', () => {
    expect(() =>
      resample(
        profile,
        reports(10, () => 0),
        [],
        [{ startMs: T - 1, stopMs: T + 100, task: 'x' }],
        30,
      ),
    ).toThrow(/servo 1 \(shoulder_pan\) has no stored position at or before/);
  });

  test('frame count is whole frame periods of the episode', () => {
    expect(frameCount({ startMs: 0, stopMs: 3000, task: '' }, 30)).toBe(90);
    expect(frameCount({ startMs: 0, stopMs: 3049, task: '' }, 30)).toBe(91);
    expect(frameCount({ startMs: 0, stopMs: 20, task: '' }, 30)).toBe(0);
  });
});

describe('dataset', () => {
  test('episodes share task indices by text; global indices run on', () => {
    const eps = resample(
      profile,
      reports(200, (k) => k),
      [],
      [
        { startMs: T, stopMs: T + 1000, task: 'pick' },
        { startMs: T + 1500, stopMs: T + 2000, task: 'place' },
        { startMs: T + 2500, stopMs: T + 3000, task: 'pick' },
      ],
      10,
    );
    const d = buildDataset(profile, eps, 10);
    expect(d.tasks).toEqual(['pick', 'place']);
    expect(d.episodes.map((e) => [e.dataset_from_index, e.dataset_to_index, e.tasks])).toEqual([
      [0, 10, ['pick']],
      [10, 15, ['place']],
      [15, 20, ['pick']],
    ]);
    expect(d.data.task_index.slice(9, 16)).toEqual([0, 1, 1, 1, 1, 1, 0]);
    expect(d.info).toMatchObject({
      codebase_version: 'v3.0',
      total_episodes: 3,
      total_frames: 20,
      total_tasks: 2,
      robot_type: 'so101_follower',
    });
  });

  test('statistics per dimension: population std, linear quantiles', () => {
    const s = featureStats([
      [0, 10],
      [1, 10],
      [2, 10],
      [3, 10],
      [4, 10],
    ]);
    expect(s).toMatchObject({
      min: [0, 10],
      max: [4, 10],
      mean: [2, 10],
      count: [5],
      q50: [2, 10],
    });
    expect(s.std[0]).toBeCloseTo(Math.SQRT2, 12);
    expect(s.q10[0]).toBeCloseTo(0.4, 12);
  });
});
