/**
 * An imported LeRobot episode's video (core/dataset/episodeVideo.ts): which MP4 holds it (v3.0:
 * a camera file shared by many episodes, found through meta/episodes; v2.1: its own file), and
 * the replay time → media time mapping, which puts every paused instant on the episode's own
 * frame even where LeRobot's float32 timestamps fall short of it.
 */
import { describe, expect, test } from 'vitest';
import {
  cameraName,
  clipSegment,
  formatPath,
  v21Clip,
  v3Clip,
  videoKeys,
} from '../src/core/dataset/episodeVideo.ts';
import { videoAt } from '../src/core/replay/videoAt.ts';

const KEY = 'observation.images.front';
const V3 = {
  fps: 30,
  video_path: 'videos/{video_key}/chunk-{chunk_index:03d}/file-{file_index:03d}.mp4',
  features: {
    'observation.state': { dtype: 'float32' },
    [KEY]: { dtype: 'video' },
    'observation.images.wrist': { dtype: 'video' },
  },
};
/** meta/episodes row of an episode 2.0 s into file 3 of chunk 1. */
const ROW = {
  episode_index: 1,
  [`videos/${KEY}/chunk_index`]: 1n,
  [`videos/${KEY}/file_index`]: 3n,
  [`videos/${KEY}/from_timestamp`]: 2.0,
  [`videos/${KEY}/to_timestamp`]: 3.5,
};

describe('where the clip is', () => {
  test('the video features, by camera', () => {
    expect(videoKeys(V3)).toEqual([KEY, 'observation.images.wrist']);
    expect(videoKeys({})).toEqual([]);
    expect(cameraName(KEY)).toBe('front');
  });

  test("v3.0: the file and time range meta/episodes gives, in info.json's path template", () => {
    expect(v3Clip(V3, KEY, ROW)).toEqual({
      key: KEY,
      path: `videos/${KEY}/chunk-001/file-003.mp4`,
      fromS: 2,
      toS: 3.5,
    });
    expect(v3Clip(V3, 'observation.images.wrist', ROW)).toBe(
      'meta/episodes has no videos/observation.images.wrist/chunk_index, videos/observation.images.wrist/file_index, videos/observation.images.wrist/from_timestamp, videos/observation.images.wrist/to_timestamp for episode 1',
    );
  });

  test("v2.1: the episode's own file, its chunk from chunks_size", () => {
    const info = { fps: 10, chunks_size: 1000 };
    expect(v21Clip(info, KEY, 1234, 25)).toEqual({
      key: KEY,
      path: `videos/chunk-001/${KEY}/episode_001234.mp4`,
      fromS: 0,
      toS: 2.5,
    });
  });

  test('a template naming what LeRobot does not give is an error', () => {
    expect(() => formatPath('videos/{camera}.mp4', { video_key: KEY })).toThrow(
      'video_path videos/{camera}.mp4 needs camera',
    );
  });
});

describe('replay time → media time', () => {
  const clip = v3Clip(V3, KEY, ROW);
  if (typeof clip === 'string') throw new Error(clip);
  const start = 1_700_000_000_123;
  const segments = [clipSegment(clip, start, 30)];

  test("every frame's instant shows that frame of the shared file, not its neighbour", () => {
    for (let k = 0; k < 45; k++) {
      const ts = Math.fround(k / 30); // LeRobot's float32 timestamp
      const at = videoAt(segments, start + ts * 1000)!;
      // Frame k of the episode is the file's frame 60 + k: shown for media times [pts, next pts).
      expect(Math.floor(at.offsetS * 30), `frame ${k}`).toBe(60 + k);
      expect(at.segment.name).toBe(`videos/${KEY}/chunk-001/file-003.mp4`);
    }
  });

  test("the clip covers the episode's last frame and ends with it", () => {
    const last = videoAt(segments, start + (44 / 30) * 1000)!;
    expect(last.offsetS).toBeLessThan(3.5);
    expect(videoAt(segments, start + 1500)).toBeNull();
  });
});
