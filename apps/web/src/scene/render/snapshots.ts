/**
 * Copies of the page's state as the render worker gets them (./messages.ts): plain values and
 * typed arrays, safe to post, no longer tied to the page's live objects.
 */
import type * as THREE from 'three';
import type { TargetPreview } from '../../core/store/TargetPreview.ts';
import type { CameraState, TargetState } from './messages.ts';

export function cameraState(c: THREE.PerspectiveCamera): CameraState {
  return {
    position: [c.position.x, c.position.y, c.position.z],
    quaternion: [c.quaternion.x, c.quaternion.y, c.quaternion.z, c.quaternion.w],
    fov: c.fov,
    near: c.near,
    far: c.far,
  };
}

export function snapshotTarget(t: TargetPreview): TargetState {
  return {
    active: t.active,
    x: t.x,
    y: t.y,
    z: t.z,
    code: t.code,
    angles: Float64Array.from(t.angles),
    hitJoint: t.hitJoint,
    ghostEnabled: t.ghostEnabled,
    refused: t.refused,
    refusedAngles: Float64Array.from(t.refusedAngles),
    refusedJoint: t.refusedJoint,
  };
}
