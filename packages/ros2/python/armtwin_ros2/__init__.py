"""armtwin's ROS 2 side: the rclpy bridge that @armtwin/ros2 runs (bridge.py), and a stand-in for
an arm's joint trajectory controller (test_arm.py). Message conversions live in messages.py."""
