/**
 * A motion request's plan as Foxglove shows it: the HUD's ghost of a plan lives in the page, but
 * every plan the arm makes is told on the wire (`arm/{id}/feedback`, docs/protocol.md § Motion
 * requests) with where it ends (`end`, µs by servo id, on `planned` and on `executing` /
 * `replanned`). That end pose, in the profile's joints (URDF names and units; a servo the plan
 * leaves out stays where it was last reported), is what `/{arm}/plan` carries and `/{arm}/plan_tf`
 * draws as a second arm (frames prefixed `plan/`). Pure.
 */
import { jointFromPwm, type Profile } from '@armtwin/robot';

export interface PlannedPose {
  id: string;
  /** `planned`, or `replanned` (a plan made again during execution). */
  status: 'planned' | 'replanned';
  mode: string;
  durationMs: number;
  /** The arm's time of the feedback (undefined: none given). */
  t: number | undefined;
  /** Each profile joint, servo order. */
  joints: { name: string; position: number }[];
}

const isObject = (v: unknown): v is Record<string, unknown> => typeof v === 'object' && v !== null;

/**
 * The plan a feedback payload tells of, or null for one that tells of none (another status) and
 * 'unreadable' for one that is not feedback at all.
 */
export function plannedPose(
  profile: Profile,
  payload: Uint8Array,
  reported: ReadonlyMap<string, number>,
): PlannedPose | null | 'unreadable' {
  let f: unknown;
  try {
    f = JSON.parse(new TextDecoder().decode(payload));
  } catch {
    return 'unreadable';
  }
  if (!isObject(f) || typeof f.status !== 'string') return 'unreadable';
  const status =
    f.status === 'planned'
      ? 'planned'
      : f.status === 'executing' && f.event === 'replanned'
        ? 'replanned'
        : null;
  if (!status) return null;
  const end = f.end;
  if (!isObject(end)) return 'unreadable';
  const joints = profile.servos.map((s) => {
    const us = end[String(s.id).padStart(3, '0')];
    const position =
      typeof us === 'number' && Number.isFinite(us)
        ? jointFromPwm(s, us)
        : (reported.get(s.joint) ?? NaN);
    return { name: s.joint, position };
  });
  return {
    id: typeof f.id === 'string' ? f.id : '',
    status,
    mode: typeof f.mode === 'string' ? f.mode : '',
    durationMs: typeof f.durationMs === 'number' ? f.durationMs : 0,
    t: typeof f.t === 'number' && Number.isFinite(f.t) ? f.t : undefined,
    joints,
  };
}
