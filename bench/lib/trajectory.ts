/**
 * A scripted trajectory on an arm's control topic: group moves to `poses` (µs, servos 000…) in
 * turn, each taking `moveMs`, one every `stepMs`, the first at once. `stop()` ends it.
 */
import type { MqttClient } from 'mqtt';

export interface Trajectory {
  poses: readonly (readonly number[])[];
  moveMs: number;
  stepMs: number;
}

export function startTrajectory(client: MqttClient, arm: string, t: Trajectory): () => void {
  let step = 0;
  const send = () => {
    const pose = t.poses[step++ % t.poses.length]!;
    client.publish(`arm/${arm}/control`, groupMove(pose, t.moveMs), { qos: 1 });
  };
  send();
  const timer = setInterval(send, t.stepMs);
  return () => clearInterval(timer);
}

/**
 * The browser and twin sections' scripted trajectory: four poses of the demo arm (µs, servos
 * 000–005) visited in turn, each move 1000 ms, one every 1500 ms.
 */
export const SCRIPTED_TRAJECTORY: Trajectory = {
  poses: [
    [1500, 1500, 1500, 1500, 1500, 1500],
    [1900, 1300, 1200, 1700, 1650, 1800],
    [1100, 1700, 1800, 1300, 1350, 1600],
    [1500, 1200, 1400, 1900, 1500, 1500],
  ],
  moveMs: 1000,
  stepMs: 1500,
};

/** A group move of every servo to `pose` (µs) in `moveMs`, as one control payload. */
export function groupMove(pose: readonly number[], moveMs: number): string {
  const ms = String(moveMs).padStart(4, '0');
  return `{${pose.map((p, i) => `#00${i}P${p}T${ms}!`).join('')}}`;
}
