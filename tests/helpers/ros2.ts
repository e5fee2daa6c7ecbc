/**
 * ROS 2 for the integration tests: the real rclpy and FastDDS from the venv that
 * scripts/install-ros2.sh makes (missing is an error naming the fix, not a skip), a ROS domain of
 * the test's own (so two runs on one machine never see each other's topics), the ROS 2 side of a
 * test as a bridge process (`Ros2Bridge`), and the test arm that stands in for ros2_control.
 */
import { spawn } from 'node:child_process';
import readline from 'node:readline';
import { Ros2Bridge, ros2Env, ros2Python } from '@armtwin/ros2';
import type { Child } from '../integration/sim-helpers.ts';

/** A ROS_DOMAIN_ID for this test process: 100–199 by pid (0 is everyone's default). */
export const testDomain = (): number => 100 + (process.pid % 100);

/** The test's own ROS 2 node (a subscriber and publisher like any ROS 2 program). */
export const startRos2Side = (domain: number): Promise<Ros2Bridge> =>
  Ros2Bridge.start({ domain, nodeName: `armtwin_test_${process.pid}` });

/**
 * python/armtwin_ros2/test_arm.py: joint states out, JointTrajectory in, like a
 * joint_trajectory_controller; resolved once it is up. `pause()` / `resume()` its joint states.
 */
export async function startTestArm(
  args: string[],
): Promise<Child & { pause(): void; resume(): void }> {
  const proc = spawn(ros2Python(), ['-m', 'armtwin_ros2.test_arm', ...args], {
    env: ros2Env(),
    stdio: ['pipe', 'pipe', 'pipe'],
  });
  let out = '';
  proc.stderr.on('data', (d: Buffer) => (out += d.toString()));
  await new Promise<void>((resolve, reject) => {
    readline.createInterface({ input: proc.stdout }).once('line', () => resolve());
    proc.once('exit', (code) => reject(new Error(`test arm exited (${code}): ${out}`)));
  });
  return {
    proc,
    output: () => out,
    stop: async () => {
      proc.stdin.end();
      const timer = setTimeout(() => proc.kill('SIGKILL'), 5000);
      await new Promise((r) => (proc.exitCode === null ? proc.once('exit', r) : r(null)));
      clearTimeout(timer);
      return proc.exitCode;
    },
    pause: () => proc.stdin.write('pause\n'),
    resume: () => proc.stdin.write('resume\n'),
  };
}
