/**
 * The arms drawn from one robot's URDF: the live arm with its tracking paint, the ghost and,
 * when a replay is given, the replay's sibling, all posed through the robot's joint map. Built
 * and swapped by the scene runtime (./render/SceneRuntime.ts).
 */
import type * as THREE from 'three';
import type { JointMap } from '../core/robots/robotSpec.ts';
import { Ghost, ghostMaterial } from './Ghost.ts';
import { PosedRobot } from './PosedRobot.ts';
import { ReplaySibling, siblingMaterial } from './ReplaySibling.ts';
import type { SceneFrame } from './render/SceneFrame.ts';
import { RobotModelLoader, solidMaterial, type MeshFailure } from './loadRobot.ts';
import { TrackingPaint } from './TrackingPaint.ts';

export interface ArmSet {
  live: PosedRobot;
  /** The live arm's links painted by tracking error. */
  tracking: TrackingPaint;
  ghost: Ghost;
  /** The replay's sibling (null without a replay). */
  sibling: ReplaySibling | null;
  /** The live arm's meshes that could not be loaded (left out; the rest is drawn). */
  failures: MeshFailure[];
}

/**
 * Loads `urdfUrl` as a new set of arms (not yet in any scene); rejects with a readable message
 * when the URDF cannot be used. All three read the runtime's snapshot `frame`. The live arm is
 * posed at once from `frame.rendered`: the store is sampled only when the arm moves, and an arm at rest may not report a change for a long
 * while (a fleet switch showed zeros).
 */
export async function loadArmSet(
  urdfUrl: string,
  joints: JointMap,
  frame: SceneFrame,
  withSibling: boolean,
): Promise<ArmSet> {
  const loader = new RobotModelLoader(urdfUrl);
  const [built, builtGhost, builtSibling] = await Promise.all([
    loader.build(solidMaterial),
    loader.build(ghostMaterial),
    withSibling ? loader.build(siblingMaterial) : null,
  ]);
  const live = new PosedRobot(built.robot, joints);
  live.pose(frame.rendered);
  return {
    live,
    tracking: new TrackingPaint(built.robot, joints.names),
    ghost: new Ghost(new PosedRobot(builtGhost.robot, joints), frame),
    sibling: builtSibling
      ? new ReplaySibling(new PosedRobot(builtSibling.robot, joints), frame)
      : null,
    failures: built.failures,
  };
}

/** Puts `next` in `world` in place of `prev` (its robots removed, its paint disposed). */
export function swapArmSet(world: THREE.Object3D, prev: ArmSet | null, next: ArmSet): void {
  if (prev) {
    for (const old of [prev.live.robot, prev.ghost.robot, prev.sibling?.robot])
      old?.removeFromParent();
    prev.tracking.dispose();
  }
  world.add(next.live.robot, next.ghost.robot);
  if (next.sibling) world.add(next.sibling.robot);
}
