/**
 * The controllers' keep-out rule in one call (docs/protocol.md, "Keep-out zones"): the floor
 * (the goal pose, floor.ts), then the zones and self-collision (the path, zones.ts). What the
 * simulator and the bus gateway answer as `$ERR:floor: …` or `$ERR:zone: …`.
 */
import { checkFloorMove } from '../floor.ts';
import type { MotionRobot } from '../robot.ts';
import { checkZonesMove, type ZoneHit } from './zones.ts';

/** The refusal kinds of `keepOutReason`, as the `$ERR` text starts (`floor: …`). */
export const KEEP_OUT_KINDS = ['floor', 'zone'] as const;
export type KeepOutKind = (typeof KEEP_OUT_KINDS)[number];

/**
 * Why a move from pose `from` to pose `to` (pulses, profile order) may not run, or '' when it
 * may: `floor: tip 12.0 mm below the floor (…)` or `zone: forearm in "table" on the way`.
 */
export function keepOutReason(
  robot: MotionRobot,
  from: ArrayLike<number>,
  to: ArrayLike<number>,
): string {
  const floor = checkFloorMove(robot, from, to);
  if (!floor.ok) return `floor: ${floor.message}`;
  const zone = checkZonesMove(robot, from, to);
  return zone.ok ? '' : `zone: ${shortReason(zone)}`;
}

/**
 * A collision in the few words a `$ERR` frame holds (its text is cut at 58 characters):
 * `hand in "table"`, `hand on base` (self-collision), `… on the way` when between the poses.
 */
export function shortReason(hit: ZoneHit): string {
  const what =
    hit.kind === 'zone' ? `${hit.link} in "${hit.other}"` : `${hit.link} on ${hit.other}`;
  return hit.at < 1 ? `${what} on the way` : what;
}

/** The kind of a `keepOutReason` (`floor` or `zone`), for counting refusals. */
export function keepOutKind(reason: string): KeepOutKind {
  return reason.startsWith('zone:') ? 'zone' : 'floor';
}

/** What the page says about a move the keep-out rules refuse: its words and the link to paint. */
export type KeepOutMoveCheck =
  | { ok: true }
  | {
      ok: false;
      kind: 'floor' | 'zone' | 'self';
      /** `tip 10.9 mm below the floor (z −10.9 < 0)`, `on the way: hand 3.0 mm into zone "table"`. */
      message: string;
      /** The URDF joint whose child link collides ('' for the floor, which names a point). */
      joint: string;
    };

/** The page's check of a jog or a target before it is sent: the floor, then the zones. */
export function checkKeepOutMove(
  robot: MotionRobot,
  from: ArrayLike<number>,
  to: ArrayLike<number>,
): KeepOutMoveCheck {
  const floor = checkFloorMove(robot, from, to);
  if (!floor.ok) return { ok: false, kind: 'floor', message: floor.message, joint: '' };
  const zone = checkZonesMove(robot, from, to);
  return zone.ok ? zone : { ok: false, kind: zone.kind, message: zone.message, joint: zone.joint };
}
