import { describe, expect, it } from 'vitest';
import { concatList, episodeVideoArgs, imageStats } from '../src/export/lerobot/index.ts';

const seg = (startMs: number, endMs: number) => ({ file: `/rec/${startMs}.mp4`, startMs, endMs });

describe("a camera's video for the LeRobot export", () => {
  it('places each segment at its own time, so a gap in the recording stays a gap', () => {
    const list = concatList(
      [seg(4000, 6000), seg(1000, 3000), seg(9000, 11000), seg(20000, 22000)],
      2500,
      9500,
    )!;
    expect(list.originMs).toBe(1000);
    expect(list.text).toBe(
      [
        'ffconcat version 1.0',
        "file '/rec/1000.mp4'",
        'duration 3.000', // to the next segment's start, not the file's own 2 s
        "file '/rec/4000.mp4'",
        'duration 5.000',
        "file '/rec/9000.mp4'",
        '',
      ].join('\n'),
    );
    expect(concatList([seg(1000, 3000)], 3500, 4000)).toBeNull();
  });

  it('asks ffmpeg for exactly the episode’s frames at the dataset fps, from its start', () => {
    const args = episodeVideoArgs('/w/list', 1.5, 90, 30, '/w/out.mp4');
    expect(args.join(' ')).toContain(
      '-vf setpts=PTS-1.500000/TB,fps=fps=30:start_time=0:round=near,tpad=stop_mode=clone:stop=-1',
    );
    expect(args.join(' ')).toContain('-frames:v 90 -c:v libx264');
    expect(args.join(' ')).toContain('-pix_fmt yuv420p');
    expect(args.at(-1)).toBe('/w/out.mp4');
  });
});

describe("a video feature's statistics", () => {
  it('are per channel in 0–1, shaped [3, 1, 1], counted in frames', () => {
    // two pixels: pure red and mid grey
    const s = imageStats(new Uint8Array([255, 0, 0, 51, 51, 51]), 1);
    expect(s.min).toEqual([[[0.2]], [[0]], [[0]]]);
    expect(s.max).toEqual([[[1]], [[0.2]], [[0.2]]]);
    expect((s.mean as number[][][]).map((c) => c[0]![0])).toEqual([0.6, 0.1, 0.1]);
    expect(s.count).toEqual([1]);
    expect(Object.keys(s)).toEqual(expect.arrayContaining(['std', 'q01', 'q50', 'q99']));
  });
});
