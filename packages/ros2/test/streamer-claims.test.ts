/** The frame streamer's timing on a manual clock, and the claim keeper's take / beat / release. */
import { expect, test } from 'vitest';
import { OPERATOR_BEAT_MS } from '@armtwin/protocol';
import { FakeClock } from '@armtwin/protocol/fake-clock';
import { ClaimKeeper } from '../src/claim-keeper.ts';
import { FrameStreamer } from '../src/frame-streamer.ts';

test('frames go at their times; a new run replaces the one under way', () => {
  const clock = new FakeClock();
  const sent: string[] = [];
  const s = new FrameStreamer(clock, (f) => sent.push(f));
  s.play([
    { at: 0, ms: 100, frame: 'a' },
    { at: 100, ms: 100, frame: 'b' },
    { at: 200, ms: 100, frame: 'c' },
  ]);
  expect(sent).toEqual(['a']);
  clock.advance(150);
  expect(sent).toEqual(['a', 'b']);
  s.play([
    { at: 0, ms: 50, frame: 'x' },
    { at: 500, ms: 50, frame: 'y' },
  ]);
  clock.advance(200);
  expect(sent).toEqual(['a', 'b', 'x']);
  expect(s.running).toBe(true);
  s.cancel();
  clock.advance(1000);
  expect(sent).toEqual(['a', 'b', 'x']);
});

test('with take: claims a free arm, beats while holding, never takes a held one, releases', () => {
  const clock = new FakeClock();
  const claims: string[] = [];
  const k = new ClaimKeeper('ros2', true, clock, (p) => claims.push(p));
  k.onHolder({ user: 'alice', requests: [] });
  expect(claims).toEqual([]);
  k.onHolder({ user: null, requests: [] });
  expect(claims).toEqual(['take']);
  k.onHolder({ user: 'ros2', requests: [] });
  clock.advance(OPERATOR_BEAT_MS * 3);
  expect(claims).toEqual(['take', 'beat', 'beat', 'beat']);
  k.onHolder({ user: 'alice', requests: [] }); // taken over: no more beats
  clock.advance(OPERATOR_BEAT_MS * 3);
  expect(claims.length).toBe(4);
  k.onHolder({ user: 'ros2', requests: [] });
  k.release();
  clock.advance(OPERATOR_BEAT_MS * 3);
  expect(claims.at(-1)).toBe('release');
});

test('without take: follows the holder record and claims nothing', () => {
  const claims: string[] = [];
  const k = new ClaimKeeper('ros2', false, new FakeClock(), (p) => claims.push(p));
  k.onHolder({ user: null, requests: [] });
  k.release();
  expect(claims).toEqual([]);
});
