import { describe, expect, it } from 'vitest';
import { compareRuns, traceAt, type RunTrace } from '../src/core/plan/compareRuns.ts';

const trace = (rows: [number, number[]][]): RunTrace => ({
  t: rows.map((r) => r[0]),
  angles: rows.map((r) => Float64Array.from(r[1])),
});

describe('predicted vs actual', () => {
  it('interpolates the rehearsal at any time since the start, held at its ends', () => {
    const p = trace([
      [0, [0, 10]],
      [100, [10, 10]],
      [200, [20, 0]],
    ]);
    expect(traceAt(p, 0, 50)).toBeCloseTo(5);
    expect(traceAt(p, 1, 150)).toBeCloseTo(5);
    expect(traceAt(p, 0, -10)).toBe(0);
    expect(traceAt(p, 0, 999)).toBe(20);
  });

  it('gives each servo its largest and mean error; an unreported servo has none', () => {
    const p = trace([
      [0, [0, 0, NaN]],
      [50, [5, 0, NaN]],
      [100, [10, 0, NaN]],
    ]);
    const a = trace([
      [0, [1, 0, 5]],
      [50, [5, 2, 5]],
      [100, [7, 0, 5]],
    ]);
    const e = compareRuns(p, a, 3);
    expect(e[0]!.maxDeg).toBeCloseTo(3);
    expect(e[0]!.meanDeg).toBeCloseTo((1 + 0 + 3) / 3);
    expect(e[1]!.maxDeg).toBeCloseTo(2);
    expect(e[2]!.maxDeg).toBeNaN();
    expect(e[2]!.samples).toBe(0);
  });
});

describe('runs lined up where they first move', () => {
  it('the same motion started later after its click has no error', () => {
    const move = (delay: number) =>
      trace([
        [0, [0, 5]],
        [delay, [0, 5]],
        [delay + 100, [10, 5]],
        [delay + 200, [20, 5]],
        [delay + 300, [20, 5]],
      ]);
    const e = compareRuns(move(50), move(400), 2);
    expect(e[0]!.maxDeg).toBeCloseTo(0);
    expect(e[1]!.maxDeg).toBeCloseTo(0);
  });

  it('a lag inside the motion still shows', () => {
    const p = trace([
      [0, [0]],
      [100, [10]],
      [200, [20]],
    ]);
    const a = trace([
      [0, [0]],
      [100, [10]],
      [200, [15]],
    ]);
    expect(compareRuns(p, a, 1)[0]!.maxDeg).toBeCloseTo(5);
  });
});

describe('Replay run', () => {
  it('a run becomes a replay record (ids by slot, angles at polarity 1, times from the start)', async () => {
    const { traceRecord } = await import('../src/core/plan/RunReplay.ts');
    const r = traceRecord(
      trace([
        [0, [10, 20]],
        [100, [NaN, 30]],
      ]),
      [1, -1],
      1000,
    );
    expect(r.ids).toEqual(['000', '001']);
    expect(r.times).toEqual([1000, 1100]);
    expect(r.angles).toEqual([
      [10, -20],
      [null, -30],
    ]);
    expect([r.start, r.stop]).toEqual([1000, 1100]);
  });

  it('plays the actual run as the sibling and the rehearsal as the ghost on the replay clock', async () => {
    const { RunReplay } = await import('../src/core/plan/RunReplay.ts');
    const { ReplayPlayer } = await import('../src/core/replay/ReplayPlayer.ts');
    const player = new ReplayPlayer([1, 1]);
    const replay = new RunReplay(player);
    const out = new Float64Array(2);
    expect(replay.sample(0, out)).toBe(false);
    const actual = trace([
      [0, [0, 0]],
      [200, [12, 0]],
    ]);
    const rehearsal = trace([
      [0, [0, 0]],
      [200, [10, 4]],
    ]);
    replay.play(actual, rehearsal, [1, 1]);
    expect(replay.playing).toBe(true);
    player.pause();
    player.seek(player.clock.start + 100);
    player.update(0);
    expect(Array.from(player.angles)).toEqual([6, 0]); // actual, half-way
    expect(replay.sample(0, out)).toBe(true);
    expect(Array.from(out)).toEqual([5, 2]); // predicted, half-way
    replay.close();
    expect(player.record).toBeNull();
    expect(replay.sample(0, out)).toBe(false);
  });
});
