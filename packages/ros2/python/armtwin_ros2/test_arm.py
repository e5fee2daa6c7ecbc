"""A ROS 2 arm for tests and demos: a stand-in for ros2_control's joint_trajectory_controller and
joint_state_broadcaster, which cannot be installed here (no wheels).

It publishes sensor_msgs/JointState on --joint-states at --rate Hz, and executes every
trajectory_msgs/JointTrajectory received on --trajectory by linear interpolation from where the
joints are when it arrives (joints the trajectory does not name stay where they are, as with the
controller's allow_partial_joints_goal: true). A new trajectory replaces the one under way. As the
controller's topic interface does, it refuses whole (logged) a trajectory without points or joint
names, one that names a joint the arm does not have, and one with a point lacking a position.

stdin lines `pause` / `resume` stop and restart the joint states (an arm whose driver hangs);
stdout says {"ev":"ready",...} once the node is up.
"""
import argparse
import json
import sys
import threading
import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.qos import QoSProfile, ReliabilityPolicy
from sensor_msgs.msg import JointState
from trajectory_msgs.msg import JointTrajectory


def sample(start, points, t_ms):
    """Positions at t_ms after the start: linear from `start` through `points`
    [(time_ms, positions)], held at the last point after it."""
    prev_t, prev = 0.0, start
    for t, pos in points:
        if t_ms < t:
            u = (t_ms - prev_t) / (t - prev_t) if t > prev_t else 1.0
            return [a + (b - a) * u for a, b in zip(prev, pos)]
        prev_t, prev = t, pos
    return list(prev)


class TestArm:
    def __init__(self, node, args):
        self.node = node
        self.joints = args.joints
        self.positions = list(args.initial)
        self.velocities = [0.0] * len(self.joints)
        self.motion = None  # (t0 seconds, start positions, [(t_ms, positions)])
        self.paused = False
        self.rate = args.rate
        self.lock = threading.Lock()
        qos = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE)
        self.pub = node.create_publisher(JointState, args.joint_states, qos)
        node.create_subscription(JointTrajectory, args.trajectory, self.on_trajectory, qos)
        node.create_timer(1.0 / args.rate, self.tick)

    def on_trajectory(self, msg):
        if not msg.joint_names or not msg.points:
            self.node.get_logger().warning('trajectory refused: no joint names or no points')
            return
        unknown = [n for n in msg.joint_names if n not in self.joints]
        if unknown:
            self.node.get_logger().warning(f'trajectory refused: unknown joints {unknown}')
            return
        if any(len(p.positions) != len(msg.joint_names) for p in msg.points):
            self.node.get_logger().warning('trajectory refused: a point without every position')
            return
        with self.lock:
            start = list(self.positions)
            index = [self.joints.index(n) for n in msg.joint_names]
            points = []
            for p in msg.points:
                full = list(points[-1][1]) if points else list(start)
                for k, i in enumerate(index):
                    full[i] = p.positions[k]
                t = p.time_from_start.sec * 1000 + p.time_from_start.nanosec / 1e6
                points.append((t, full))
            self.motion = (time.monotonic(), start, points)

    def tick(self):
        with self.lock:
            if self.motion is not None:
                t0, start, points = self.motion
                t_ms = (time.monotonic() - t0) * 1000
                nxt = sample(start, points, t_ms)
                dt = 1.0 / self.rate
                self.velocities = [(b - a) / dt for a, b in zip(self.positions, nxt)]
                self.positions = nxt
                if t_ms >= points[-1][0]:
                    self.motion = None
            else:
                self.velocities = [0.0] * len(self.joints)
            if self.paused:
                return
            msg = JointState()
            msg.header.stamp = self.node.get_clock().now().to_msg()
            msg.name = list(self.joints)
            msg.position = list(self.positions)
            msg.velocity = list(self.velocities)
        self.pub.publish(msg)


def floats(text):
    return [float(x) for x in text.split(',')] if text else []


def main(argv=None):
    parser = argparse.ArgumentParser(prog='armtwin_ros2.test_arm')
    parser.add_argument('--joints', required=True, help='joint names, comma-separated')
    parser.add_argument('--initial', default='', help='initial positions (rad or m), comma-separated')
    parser.add_argument('--rate', type=float, default=50.0, help='joint state rate, Hz')
    parser.add_argument('--joint-states', default='/joint_states')
    parser.add_argument('--trajectory', default='/joint_trajectory_controller/joint_trajectory')
    parser.add_argument('--domain', type=int, default=None)
    parser.add_argument('--name', default='armtwin_test_arm')
    args = parser.parse_args(argv)
    args.joints = args.joints.split(',')
    args.initial = floats(args.initial) or [0.0] * len(args.joints)
    if len(args.initial) != len(args.joints):
        parser.error(f'--initial has {len(args.initial)} values for {len(args.joints)} joints')
    if args.domain is None:
        rclpy.init()
    else:
        rclpy.init(domain_id=args.domain)
    node = rclpy.create_node(args.name)
    arm = TestArm(node, args)

    def spin():
        try:
            rclpy.spin(node)
        except ExternalShutdownException:
            pass

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    sys.stdout.write(json.dumps({'ev': 'ready', 'joints': args.joints}) + '\n')
    sys.stdout.flush()
    for line in sys.stdin:
        word = line.strip()
        if word in ('pause', 'resume'):
            with arm.lock:
                arm.paused = word == 'pause'
    rclpy.try_shutdown()
    spinner.join(timeout=5)
    node.destroy_node()


if __name__ == '__main__':
    main()
