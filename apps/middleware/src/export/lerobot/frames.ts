/**
 * An arm's stored history resampled onto a LeRobot dataset's clock: for each episode, one frame
 * every 1/fps s from its start, `floor(duration × fps)` frames. Each frame's `observation.state`
 * is every servo's last stored position at or before the tick (sample-and-hold, no
 * interpolation: a value LeRobot sees was reported by the arm), and its `action` the last
 * commanded target at or before the tick, held between commands (before the first command, the
 * state). Values are in LeRobot's units for the SO follower (`lerobotValue`, @armtwin/robot:
 * joints in degrees, the gripper in 0–100 % of its limits). Pure, no I/O.
 */
import { angleFromPwm } from '@armtwin/protocol';
import { lerobotValue, type Profile } from '@armtwin/robot';
import type { CommandRow, ServoRow } from '../recording.ts';

export interface Episode {
  /** Epoch ms, included. */
  startMs: number;
  /** Epoch ms, excluded. */
  stopMs: number;
  /** LeRobot's `single_task`. */
  task: string;
}

export interface EpisodeFrames {
  episode: Episode;
  /** Seconds from the episode's start: k / fps. */
  timestamps: number[];
  /** One row per frame, one value per profile servo, in LeRobot's units. */
  state: number[][];
  action: number[][];
}

type Servo = Profile['servos'][number];

export { lerobotValue };

/** Degrees a stored point holds, or undefined when it holds no position (health only). */
function degreesOf(row: { angle?: number; pwm?: number }): number | undefined {
  if (row.angle !== undefined) return row.angle;
  if (row.pwm !== undefined) return angleFromPwm(row.pwm);
  return undefined;
}

/** The frame count of an episode at `fps`: whole frame periods in [start, stop). */
export function frameCount(e: Episode, fps: number): number {
  return Math.floor(((e.stopMs - e.startMs) * fps) / 1000 + 1e-9);
}

/** Per servo: (ms, degrees) in time order, from rows in time order. */
function tracks(servos: readonly Servo[], rows: readonly (ServoRow | CommandRow)[]) {
  const index = new Map(servos.map((s, i) => [Number(s.id), i]));
  const out = servos.map(() => ({ ms: [] as number[], deg: [] as number[] }));
  for (const row of rows) {
    const i = index.get(Number(row.id));
    const deg = degreesOf(row);
    if (i === undefined || deg === undefined) continue;
    out[i]!.ms.push(Number(row.ns) / 1e6);
    out[i]!.deg.push(deg);
  }
  return out;
}

/** Index of the last `ms[i] <= t` at or after `from`, or from − 1 when none. */
function advance(ms: readonly number[], from: number, t: number): number {
  let i = from;
  while (i + 1 < ms.length && ms[i + 1]! <= t) i++;
  return i;
}

/**
 * The frames of each episode from a recording's rows (time order), which should start early
 * enough to hold every servo's position at the first tick. Throws naming a servo with no stored
 * position at or before an episode's first tick.
 */
export function resample(
  profile: Profile,
  servo: readonly ServoRow[],
  command: readonly CommandRow[],
  episodes: readonly Episode[],
  fps: number,
): EpisodeFrames[] {
  if (!(Number.isInteger(fps) && fps > 0)) throw new RangeError(`fps must be a whole number > 0`);
  const states = tracks(profile.servos, servo);
  const actions = tracks(profile.servos, command);
  return episodes.map((episode) => {
    const n = frameCount(episode, fps);
    const at = profile.servos.map(() => -1);
    const cmd = profile.servos.map(() => -1);
    const out: EpisodeFrames = { episode, timestamps: [], state: [], action: [] };
    for (let k = 0; k < n; k++) {
      const t = episode.startMs + (k * 1000) / fps;
      const state: number[] = [];
      const action: number[] = [];
      profile.servos.forEach((s, i) => {
        at[i] = advance(states[i]!.ms, at[i]!, t);
        cmd[i] = advance(actions[i]!.ms, cmd[i]!, t);
        if (at[i]! < 0)
          throw new Error(
            `servo ${s.id} (${s.name}) has no stored position at or before ${new Date(t).toISOString()}`,
          );
        const reported = lerobotValue(s, states[i]!.deg[at[i]!]!);
        state.push(reported);
        action.push(cmd[i]! < 0 ? reported : lerobotValue(s, actions[i]!.deg[cmd[i]!]!));
      });
      out.timestamps.push(k / fps);
      out.state.push(state);
      out.action.push(action);
    }
    return out;
  });
}
