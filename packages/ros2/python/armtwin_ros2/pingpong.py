"""Ping/pong over ROS 2 for `npm run bench` (bench/ros2.ts), seed 004's experiment on rclpy.

  echo   republishes every std_msgs/String from --ping on --pong
  ping   sends --count messages (the sequence number as text) at --rate Hz on --ping, times each
         one's return on --pong, and prints one JSON line: sent, received, lost (by sequence
         number), round trips in microseconds (p50, p99, max) and its own CPU seconds.

Both print {"ev":"ready"} once up. Reliable QoS, depth 1000, as a default-QoS rclpy app would
be apart from the depth (so a burst is not dropped by the history).
"""
import argparse
import json
import sys
import threading
import time

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.qos import QoSProfile, ReliabilityPolicy
from std_msgs.msg import String

QOS = QoSProfile(depth=1000, reliability=ReliabilityPolicy.RELIABLE)


def say(obj):
    sys.stdout.write(json.dumps(obj) + '\n')
    sys.stdout.flush()


def pct(sorted_values, p):
    if not sorted_values:
        return None
    return sorted_values[min(len(sorted_values) - 1, int(p * len(sorted_values)))]


def main(argv=None):
    ap = argparse.ArgumentParser(prog='armtwin_ros2.pingpong')
    ap.add_argument('mode', choices=['echo', 'ping'])
    ap.add_argument('--domain', type=int, default=None)
    ap.add_argument('--ping', default='/armtwin_bench/ping')
    ap.add_argument('--pong', default='/armtwin_bench/pong')
    ap.add_argument('--rate', type=float, default=1000.0)
    ap.add_argument('--count', type=int, default=60000)
    args = ap.parse_args(argv)
    rclpy.init(domain_id=args.domain) if args.domain is not None else rclpy.init()
    node = rclpy.create_node(f'armtwin_bench_{args.mode}')
    if args.mode == 'echo':
        pub = node.create_publisher(String, args.pong, QOS)
        node.create_subscription(String, args.ping, pub.publish, QOS)
        say({'ev': 'ready'})
        try:
            rclpy.spin(node)
        except (KeyboardInterrupt, ExternalShutdownException):
            pass
        return
    sent_at = {}
    rtts = []
    seen = set()
    lock = threading.Lock()

    def on_pong(m):
        now = time.perf_counter_ns()
        seq = int(m.data)
        with lock:
            if seq in seen or seq not in sent_at:
                return
            seen.add(seq)
            rtts.append((now - sent_at[seq]) / 1000)

    pub = node.create_publisher(String, args.ping, QOS)
    sub = node.create_subscription(String, args.pong, on_pong, QOS)
    spinner = threading.Thread(target=lambda: rclpy.spin(node), daemon=True)
    spinner.start()
    deadline = time.monotonic() + 20
    while (pub.get_subscription_count() == 0 or sub.get_publisher_count() == 0) and time.monotonic() < deadline:
        time.sleep(0.01)
    say({'ev': 'ready'})
    cpu0 = time.process_time()
    period = 1.0 / args.rate
    start = time.perf_counter()
    for seq in range(args.count):
        target = start + seq * period
        delay = target - time.perf_counter()
        if delay > 0:
            time.sleep(delay)
        with lock:
            sent_at[seq] = time.perf_counter_ns()
        pub.publish(String(data=str(seq)))
    end = time.monotonic() + 2.0
    while len(seen) < args.count and time.monotonic() < end:
        time.sleep(0.01)
    cpu = time.process_time() - cpu0
    with lock:
        r = sorted(rtts)
        received = len(seen)
    say({
        'ev': 'result', 'sent': args.count, 'received': received, 'lost': args.count - received,
        'rate': args.rate, 'p50_us': pct(r, 0.5), 'p99_us': pct(r, 0.99), 'max_us': r[-1] if r else None,
        'cpu_s': cpu,
    })
    rclpy.try_shutdown()
    spinner.join(timeout=5)


if __name__ == '__main__':
    main()
