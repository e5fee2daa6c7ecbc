/**
 * The HUD's command box: a line of text → a motion request (the same JSON any client sends to
 * `arm/{id}/request`). Case and extra spaces do not matter; numbers may be separated by spaces
 * or commas.
 *
 *   home | ready | rest | <any pose of the profile>   joint move to that named pose
 *   go to <pose>                                       the same
 *   open gripper | open      close gripper | close     poses `open` / `closed`
 *   move to 150 0 80 [pitch -90]                       joint move, IK at the target
 *   line to 150 0 80 [pitch -90]                       Cartesian: a straight line to it
 *   plan <any of the above>                            plan only (execute: false)
 */
import type { Profile } from '@armtwin/robot';
import { validateRequest, type MotionRequest, type RequestTarget } from './request.ts';

export type CommandResult = { ok: true; request: MotionRequest } | { ok: false; message: string };

const NUM = String.raw`(-?\d+(?:\.\d+)?)`;
const SEP = String.raw`(?:\s*,\s*|\s+)`;
const MOVE = new RegExp(
  String.raw`^(move|line)\s+to\s+${NUM}${SEP}${NUM}${SEP}${NUM}(?:${SEP}pitch\s*${NUM})?$`,
);
const GRIPPER: Record<string, string> = {
  'open gripper': 'open',
  open: 'open',
  'close gripper': 'closed',
  close: 'closed',
};

/**
 * Parses one command. With a profile, pose names are checked against it (so "open gripper" on
 * an arm without an `open` pose is refused here, not by the arm). `id` becomes the request id.
 */
export function parseCommand(text: string, id: string, profile?: Profile): CommandResult {
  let line = text.trim().toLowerCase().replace(/\s+/g, ' ');
  let execute = true;
  if (line.startsWith('plan ')) {
    execute = false;
    line = line.slice(5);
  }
  if (line === '') return { ok: false, message: 'empty command' };
  let mode: MotionRequest['mode'] = 'joint';
  let target: RequestTarget;
  const m = MOVE.exec(line);
  if (m) {
    if (m[1] === 'line') mode = 'cartesian';
    target = { x: Number(m[2]), y: Number(m[3]), z: Number(m[4]) };
    if (m[5] !== undefined) target.pitch = Number(m[5]);
  } else {
    const pose = GRIPPER[line] ?? line.replace(/^go to /, '').replace(/^pose /, '');
    if (!/^[a-z0-9_-]{1,32}$/.test(pose))
      return {
        ok: false,
        message: `not a command: "${text.trim().slice(0, 40)}" (try: home, open gripper, move to 150 0 80)`,
      };
    if (profile && !(pose in profile.poses)) {
      const what = GRIPPER[line] ? `no gripper pose "${pose}"` : `no pose "${pose}"`;
      return {
        ok: false,
        message: `${profile.name} has ${what} (poses: ${Object.keys(profile.poses).join(', ')})`,
      };
    }
    target = pose;
  }
  const r = validateRequest({ id, mode, targets: [target], execute });
  return r.ok ? r : { ok: false, message: r.message };
}
