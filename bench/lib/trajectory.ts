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
  const ms = String(t.moveMs).padStart(4, '0');
  const send = () => {
    const pose = t.poses[step++ % t.poses.length]!;
    client.publish(
      `arm/${arm}/control`,
      `{${pose.map((p, i) => `#00${i}P${p}T${ms}!`).join('')}}`,
      {
        qos: 1,
      },
    );
  };
  send();
  const timer = setInterval(send, t.stepMs);
  return () => clearInterval(timer);
}
