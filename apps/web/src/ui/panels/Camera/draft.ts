/**
 * The calibration form's draft: seven number fields as typed, to and from a camera placement.
 * Pure. A draft that is not a placement §7 would take (a blank field, one point twice, a field
 * of view outside 0–180°) gives null, and cannot be saved.
 */
import { MAX_POSE_MM, type Vec3 } from '@armtwin/camera/client';
import type { CameraPlacement } from '../../../core/cameras/CameraHub.ts';

export const AXES = ['x', 'y', 'z'] as const;

export interface Draft {
  px: string;
  py: string;
  pz: string;
  lx: string;
  ly: string;
  lz: string;
  fov: string;
}

/** mm to 0.1, degrees to 0.01: as fine as a user can see. */
const round = (v: number, places: number) => String(Number(v.toFixed(places)));

export function draftFromPlacement(p: CameraPlacement): Draft {
  const [px, py, pz] = p.pose.position.map((v) => round(v, 1)) as [string, string, string];
  const [lx, ly, lz] = p.pose.lookAt.map((v) => round(v, 1)) as [string, string, string];
  return { px, py, pz, lx, ly, lz, fov: round(p.fovDeg, 2) };
}

export function placementFromDraft(d: Draft): CameraPlacement | null {
  const num = (s: string) => (s.trim() === '' ? NaN : Number(s));
  const position: Vec3 = [num(d.px), num(d.py), num(d.pz)];
  const lookAt: Vec3 = [num(d.lx), num(d.ly), num(d.lz)];
  const fovDeg = num(d.fov);
  const ok = (v: number) => Number.isFinite(v) && Math.abs(v) <= MAX_POSE_MM;
  if (![...position, ...lookAt].every(ok)) return null;
  if (position.every((v, i) => v === lookAt[i])) return null;
  if (!(fovDeg > 0 && fovDeg < 180)) return null;
  return { pose: { position, lookAt }, fovDeg };
}
