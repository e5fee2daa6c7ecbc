/**
 * The pose the render worker draws at rest, through the page's messages: the store samples the
 * reports (src/store/ArmStore.ts, predictive twin), FrameChanges picks what to post
 * (src/scene/render/FrameChanges.ts) and the worker's DrawnPose poses the arm from the last
 * sample and course it got (src/scene/render/DrawnPose.ts). Whatever the last move looked
 * like, an arm at rest is drawn where it reported itself.
 */
import { describe, expect, it } from 'vitest';
import { angleFromPwm, encodeGroup, encodePosition } from '@armtwin/protocol';
import { ArmStore } from '../src/core/store/ArmStore.ts';
import { TargetPreview } from '../src/core/store/TargetPreview.ts';
import { FrameChanges } from '../src/scene/render/FrameChanges.ts';
import { DrawnPose } from '../src/scene/render/DrawnPose.ts';
import { emptySceneFrame, mergeFrame } from '../src/scene/render/SceneFrame.ts';
import type { FrameInput } from '../src/scene/render/messages.ts';

const T0 = 1_700_000_000_000;
/** A state report of the demo arm, its elbow (servo 2) at `elbow` µs, stamped `at` after T0. */
const report = (elbow: number, at: number) =>
  `$TIM:${T0 + at}!${encodeGroup([1500, 1500, elbow, 1500, 1500, 1500].map((p, i) => encodePosition(i, p)))}`;
const REST = angleFromPwm(1800);

/**
 * The page (store + FrameChanges) and the worker's snapshot. Reports come 20 ms apart and are
 * sampled as they arrive; `lose` names the page frames that fail before their post.
 */
function twin(elbows: number[], lose: (i: number) => boolean = () => false) {
  const store = new ArmStore();
  const changes = new FrameChanges(store, new TargetPreview(), null);
  const frame = emptySceneFrame();
  const pose = new DrawnPose(frame);
  let at = 0;
  elbows.forEach((elbow, i) => {
    store.ingest(report(elbow, at), at);
    const m: FrameInput = { type: 'frame' };
    changes.collect(m, at, false, true, null);
    if (!lose(i)) {
      mergeFrame(frame, m);
      pose.take(m);
      changes.posted(m);
    }
    at += 20;
  });
  /** The elbow as the worker poses it at page time `now`. */
  const drawnAt = (now: number) => {
    pose.poseAt(performance.timeOrigin + now);
    return frame.rendered[2];
  };
  return { drawnAt, end: at };
}

describe('the worker draws an arm at rest where it reported itself', () => {
  it('after a move whose first report at the final pose still showed a velocity', () => {
    // 1500 → 1800 µs (27° to 40.5°), then at rest: the first 1800 report, with 1700 before it,
    // gave a velocity the course went on with; the samples after it did not change.
    const { drawnAt, end } = twin([1500, 1600, 1700, 1800, 1800, 1800, 1800]);
    expect(drawnAt(end + 1000)).toBeCloseTo(REST, 6);
    expect(drawnAt(end + 60_000)).toBeCloseTo(REST, 6);
  });

  it('when the page frame that sampled the resting arm never posted it', () => {
    // The frame that first sampled the resting arm fails before its post; the next one, with
    // the same sample, carries it.
    const { drawnAt, end } = twin([1500, 1600, 1700, 1800, 1800, 1800, 1800, 1800], (i) => i === 4);
    expect(drawnAt(end + 1000)).toBeCloseTo(REST, 6);
  });

  it('and the page does not post again while nothing changes', () => {
    const store = new ArmStore();
    const changes = new FrameChanges(store, new TargetPreview(), null);
    let posted = 0;
    for (let at = 0; at < 2000; at += 20) {
      store.ingest(report(1800, at), at);
      const m: FrameInput = { type: 'frame' };
      changes.collect(m, at, false, true, null);
      if (m.rendered) posted++;
      changes.posted(m);
    }
    expect(posted).toBe(1);
  });
});
