/**
 * Distances for keep-out checks (pure, allocation-free): the signed distance from a point to a
 * zone (negative inside), the least of it along a segment, and the distance between two
 * segments. A link is a capsule (a segment and a radius), so it touches a zone when the least
 * signed distance along its segment is below its radius.
 */
import type { Zone } from '@armtwin/robot';

/** Signed distance (mm) from (x, y, z) to the zone: > 0 outside, < 0 inside. */
export function zoneDistance(zone: Zone, x: number, y: number, z: number): number {
  switch (zone.shape) {
    case 'box': {
      const { min, max } = zone;
      const qx = Math.max(min[0] - x, x - max[0]);
      const qy = Math.max(min[1] - y, y - max[1]);
      const qz = Math.max(min[2] - z, z - max[2]);
      const ox = qx > 0 ? qx : 0,
        oy = qy > 0 ? qy : 0,
        oz = qz > 0 ? qz : 0;
      const inside = qx > qy ? (qx > qz ? qx : qz) : qy > qz ? qy : qz;
      return Math.sqrt(ox * ox + oy * oy + oz * oz) + (inside < 0 ? inside : 0);
    }
    case 'cylinder': {
      const dx = x - zone.center[0],
        dy = y - zone.center[1];
      const r = Math.sqrt(dx * dx + dy * dy) - zone.radius;
      const h = zone.zMin - z > z - zone.zMax ? zone.zMin - z : z - zone.zMax;
      const or = r > 0 ? r : 0,
        oh = h > 0 ? h : 0;
      const inside = r > h ? r : h;
      return Math.sqrt(or * or + oh * oh) + (inside < 0 ? inside : 0);
    }
    case 'plane': {
      const { point: p, normal: n } = zone;
      return -((x - p[0]) * n[0] + (y - p[1]) * n[1] + (z - p[2]) * n[2]);
    }
    default: {
      const never: never = zone;
      return never;
    }
  }
}

const PHI = (Math.sqrt(5) - 1) / 2;
/** Golden-section search stops when the bracket is this short along the segment, mm. */
export const SEGMENT_SEARCH_MM = 0.25;

/**
 * The least signed distance from the segment a→b (flat xyz at `ia`, `ib` of `p`) to the zone.
 * A zone is convex, so the distance along a line is convex and a golden-section search finds
 * its minimum; a segment whose midpoint is farther than half its length plus `margin` is
 * answered at once (the distance is 1-Lipschitz), with a value above `margin`.
 */
export function segmentZoneDistance(
  zone: Zone,
  p: Float64Array,
  ia: number,
  ib: number,
  margin: number,
): number {
  const ax = p[ia]!,
    ay = p[ia + 1]!,
    az = p[ia + 2]!;
  const dx = p[ib]! - ax,
    dy = p[ib + 1]! - ay,
    dz = p[ib + 2]! - az;
  const len = Math.sqrt(dx * dx + dy * dy + dz * dz);
  const mid = zoneDistance(zone, ax + 0.5 * dx, ay + 0.5 * dy, az + 0.5 * dz);
  if (mid - len / 2 > margin || len < SEGMENT_SEARCH_MM) return mid - len / 2;
  let lo = 0,
    hi = 1;
  let c = hi - PHI * (hi - lo),
    d = lo + PHI * (hi - lo);
  let fc = zoneDistance(zone, ax + c * dx, ay + c * dy, az + c * dz),
    fd = zoneDistance(zone, ax + d * dx, ay + d * dy, az + d * dz);
  const stop = SEGMENT_SEARCH_MM / len;
  while (hi - lo > stop) {
    if (fc < fd) {
      hi = d;
      d = c;
      fd = fc;
      c = hi - PHI * (hi - lo);
      fc = zoneDistance(zone, ax + c * dx, ay + c * dy, az + c * dz);
    } else {
      lo = c;
      c = d;
      fc = fd;
      d = lo + PHI * (hi - lo);
      fd = zoneDistance(zone, ax + d * dx, ay + d * dy, az + d * dz);
    }
  }
  const ends = Math.min(
    zoneDistance(zone, ax, ay, az),
    zoneDistance(zone, ax + dx, ay + dy, az + dz),
  );
  return Math.min(fc, fd, ends);
}

/**
 * Distance between segments a→b and c→d (flat xyz in `p` at ia, ib, ic, id), mm: the closest
 * points of the two segments (Ericson, Real-Time Collision Detection, 5.1.9).
 */
export function segmentSegmentDistance(
  p: Float64Array,
  ia: number,
  ib: number,
  ic: number,
  id: number,
): number {
  const d1x = p[ib]! - p[ia]!,
    d1y = p[ib + 1]! - p[ia + 1]!,
    d1z = p[ib + 2]! - p[ia + 2]!;
  const d2x = p[id]! - p[ic]!,
    d2y = p[id + 1]! - p[ic + 1]!,
    d2z = p[id + 2]! - p[ic + 2]!;
  const rx = p[ia]! - p[ic]!,
    ry = p[ia + 1]! - p[ic + 1]!,
    rz = p[ia + 2]! - p[ic + 2]!;
  const a = d1x * d1x + d1y * d1y + d1z * d1z;
  const e = d2x * d2x + d2y * d2y + d2z * d2z;
  const f = d2x * rx + d2y * ry + d2z * rz;
  const EPS = 1e-12;
  let s: number, t: number;
  if (a <= EPS && e <= EPS) {
    s = 0;
    t = 0;
  } else if (a <= EPS) {
    s = 0;
    t = clamp01(f / e);
  } else {
    const c = d1x * rx + d1y * ry + d1z * rz;
    if (e <= EPS) {
      t = 0;
      s = clamp01(-c / a);
    } else {
      const b = d1x * d2x + d1y * d2y + d1z * d2z;
      const denom = a * e - b * b;
      s = denom > EPS ? clamp01((b * f - c * e) / denom) : 0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = clamp01((b - c) / a);
      }
    }
  }
  const cx = rx + d1x * s - d2x * t,
    cy = ry + d1y * s - d2y * t,
    cz = rz + d1z * s - d2z * t;
  return Math.sqrt(cx * cx + cy * cy + cz * cz);
}

const clamp01 = (v: number) => (v < 0 ? 0 : v > 1 ? 1 : v);
