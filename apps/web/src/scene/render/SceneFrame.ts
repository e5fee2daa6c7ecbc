/**
 * What the scene runtime (./SceneRuntime.ts) draws from: one plain snapshot of the page's state,
 * kept up to date by the page's `FrameInput` messages (./messages.ts), each of which carries the
 * parts of it that changed. The page builds those parts from its own store, target and plan
 * (./FrameChanges.ts) on whichever thread the runtime runs; the runtime's Ghost, TargetMarker and
 * ReplaySibling read the snapshot as it is — plain values, no stand-in for the page's objects.
 */
import { DEMO_ARM, type ArmProfile } from '@armtwin/ik';
import { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { FrameInput, TargetState } from './messages.ts';
import { snapshotTarget } from './snapshots.ts';

export interface SceneFrame {
  /** The arm's profile (the servos' polarities the commanded pulses are read with). */
  arm: ArmProfile;
  /** The live arm's drawn servo angles, degrees, posed for the frame drawn (./DrawnPose.ts). */
  rendered: Float64Array;
  /** The pulses this page last commanded, NaN = none. */
  commandedPwm: Float64Array;
  /** The Cartesian target and the ghost's switches. */
  target: TargetState;
  /** The plan preview's pose (the page's ghost source), null when it shows none. */
  plan: Float64Array | null;
  /** The replay sibling's pose, null while it is hidden (a new array each time it moves). */
  sibling: Float64Array | null;
}

/** The snapshot before the page's first frame: the demo arm at no pose, no target. */
export function emptySceneFrame(): SceneFrame {
  return {
    arm: DEMO_ARM,
    rendered: new Float64Array(0),
    commandedPwm: new Float64Array(0),
    target: snapshotTarget(new TargetPreview()),
    plan: null,
    sibling: null,
  };
}

/** Takes the parts `m` carries (the drawn angles are posed by ./DrawnPose.ts). */
export function mergeFrame(frame: SceneFrame, m: FrameInput): void {
  if (m.arm) frame.arm = m.arm;
  if (m.commandedPwm) frame.commandedPwm = m.commandedPwm;
  if (m.target) frame.target = m.target;
  if (m.plan !== undefined) frame.plan = m.plan;
  if (m.sibling !== undefined) frame.sibling = m.sibling;
}
