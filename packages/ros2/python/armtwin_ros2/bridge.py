"""The rclpy process that @armtwin/ros2 runs: JSON lines on stdin become ROS 2 publications and
subscriptions; every message a subscription receives comes out on stdout as a JSON line.

It makes no decision about the arm: it carries messages (packages/ros2/src/wire.ts is the wire).

  stdin   {"op":"subscribe","id":1,"topic":"/x","type":"joint_state","durable":false}
          {"op":"publish","topic":"/x","type":"string","msg":{"data":"..."},"durable":true}
          {"op":"advertise","id":2,"topic":"/y","type":"joint_trajectory","wait_ms":3000}
  stdout  {"ev":"ready","domain":0,"node":"armtwin_bridge_123"}
          {"ev":"ack","id":1,"subscribers":0}
          {"ev":"message","topic":"/x","type":"joint_state","msg":{...}}
          {"ev":"error","kind":"bad-message","message":"...","id":1}

`durable` is transient-local QoS with depth 1: a publisher keeps its last message for every
subscriber that joins later (a latched topic, as robot_description is), and a subscriber gets it.
A new publisher is matched to the subscribers already there only after discovery (tens of ms), so
a message published at once may reach nobody: `advertise` (or `publish`) with `wait_ms` first
waits up to that long for a subscriber; the ack says how many there are.
The process ends when stdin closes.
"""
import argparse
import json
import os
import sys
import threading
import time

import rclpy
from rclpy.executors import ExternalShutdownException, SingleThreadedExecutor
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy

from .messages import TYPES, from_ros, to_ros

_out_lock = threading.Lock()


def emit(event):
    line = json.dumps(event, separators=(',', ':'), allow_nan=False)
    with _out_lock:
        sys.stdout.write(line + '\n')
        sys.stdout.flush()


def qos(durable):
    if durable:
        return QoSProfile(
            depth=1,
            reliability=ReliabilityPolicy.RELIABLE,
            durability=DurabilityPolicy.TRANSIENT_LOCAL,
        )
    # Deeper than rclpy's usual 10: this process only carries messages, and a burst (a 1 kHz
    # stream while the JSON side is busy) should wait here, not be overwritten in the history.
    return QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE)


class Bridge:
    def __init__(self, node):
        self.node = node
        self.publishers = {}
        self.subscriptions = {}

    def now_ms(self):
        return self.node.get_clock().now().nanoseconds / 1e6

    def handle(self, cmd):
        op = cmd.get('op')
        kind = cmd.get('type')
        topic = cmd.get('topic')
        if op not in ('subscribe', 'publish', 'advertise'):
            raise LookupError(f'unknown op {op!r} (subscribe, publish, advertise)')
        if kind not in TYPES:
            raise LookupError(f'unknown type {kind!r} ({", ".join(TYPES)})')
        if not isinstance(topic, str):
            raise LookupError('topic must be a string')
        durable = cmd.get('durable') is True
        key = (topic, kind, durable)
        if op == 'subscribe':
            if key not in self.subscriptions:
                self.subscriptions[key] = self.node.create_subscription(
                    TYPES[kind],
                    topic,
                    lambda m, t=topic, k=kind: emit(
                        {'ev': 'message', 'topic': t, 'type': k, 'msg': from_ros(k, m)}
                    ),
                    qos(durable),
                )
            return {}
        wait_ms = cmd.get('wait_ms', 0)
        if isinstance(wait_ms, bool) or not isinstance(wait_ms, (int, float)):
            raise LookupError('wait_ms must be a number')
        msg = None if op == 'advertise' else to_ros(kind, cmd.get('msg'), self.now_ms())
        if key not in self.publishers:
            self.publishers[key] = self.node.create_publisher(TYPES[kind], topic, qos(durable))
        pub = self.publishers[key]
        deadline = time.monotonic() + min(wait_ms, 60_000) / 1000
        while pub.get_subscription_count() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        if msg is not None:
            pub.publish(msg)
        return {'subscribers': pub.get_subscription_count()}


def main(argv=None):
    parser = argparse.ArgumentParser(prog='armtwin_ros2.bridge')
    parser.add_argument('--domain', type=int, default=None, help='ROS_DOMAIN_ID (0-232)')
    parser.add_argument('--name', default=f'armtwin_bridge_{os.getpid()}', help='node name')
    args = parser.parse_args(argv)
    if args.domain is None:
        rclpy.init()
    else:
        rclpy.init(domain_id=args.domain)
    node = rclpy.create_node(args.name)
    bridge = Bridge(node)
    executor = SingleThreadedExecutor()
    executor.add_node(node)

    def spin():
        try:
            executor.spin()
        except ExternalShutdownException:
            pass

    spinner = threading.Thread(target=spin, daemon=True)
    spinner.start()
    emit({'ev': 'ready', 'domain': node.context.get_domain_id(), 'node': node.get_name()})
    for line in sys.stdin:
        if not line.strip():
            continue
        try:
            cmd = json.loads(line)
        except ValueError as e:
            emit({'ev': 'error', 'kind': 'bad-json', 'message': str(e)})
            continue
        if not isinstance(cmd, dict):
            emit({'ev': 'error', 'kind': 'bad-json', 'message': 'a command is a JSON object'})
            continue
        ident = cmd.get('id')
        try:
            reply = bridge.handle(cmd)
        except LookupError as e:
            emit({'ev': 'error', 'kind': 'bad-command', 'message': str(e), 'id': ident})
            continue
        except (ValueError, TypeError) as e:
            emit({'ev': 'error', 'kind': 'bad-message', 'message': str(e), 'id': ident})
            continue
        except Exception as e:  # rclpy's own errors: an invalid topic name, a QoS clash
            emit({'ev': 'error', 'kind': 'ros', 'message': f'{type(e).__name__}: {e}', 'id': ident})
            continue
        if ident is not None:
            emit({'ev': 'ack', 'id': ident, **reply})
    # Shut the context down first: the spinning thread leaves spin() and is joined, so nothing of
    # rclpy is still running when the interpreter exits.
    rclpy.try_shutdown()
    spinner.join(timeout=5)
    node.destroy_node()


if __name__ == '__main__':
    main()
