#!/usr/bin/env bash
# ROS 2 for `armtwin ros2` and its tests: a venv with ROS 2 Kilted's rclpy and FastDDS from PyPI
# wheels, on Debian's Python 3.11, cached outside the clone like the servo-SDK venv
# (install-deps.sh). A stamp file holds the pinned requirements: a changed pin rebuilds the venv,
# an unchanged one is kept. Idempotent, never asks. Called by install-deps.sh; runnable alone.
#
# At run time nothing needs setting by hand: the wheels ship `ros_wheels_bootstrapper.pth`, which
# re-executes the interpreter once with LD_LIBRARY_PATH pointing at the wheels' libraries
# (site-packages/ros_*.libs). packages/ros2/src/venv.ts finds the venv at the same path.
set -euo pipefail

say() { printf 'install-ros2: %s\n' "$*"; }

ROS2_DIR="${ARMTWIN_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/armtwin}/ros2-kilted"
# rclpy, FastDDS (the default middleware: rmw_fastrtps_cpp is its own wheel) and the messages
# armtwin speaks. control_msgs, tf2, robot_state_publisher and rosbridge have no wheels.
ROS2_REQS="ros-kilted-rclpy==9.1.2 ros-kilted-rmw-fastrtps-cpp==9.3.3 ros-kilted-sensor-msgs==5.5.1 ros-kilted-trajectory-msgs==5.5.1 ros-kilted-std-msgs==5.5.1 ros-kilted-builtin-interfaces==2.3.0"
ROS2_STAMP="$ROS2_DIR/.armtwin-requirements"
ROS2_CHECK='import rclpy, sensor_msgs.msg, trajectory_msgs.msg, std_msgs.msg
rclpy.init(); rclpy.create_node("armtwin_install_check").destroy_node(); rclpy.shutdown()'

if [ -x "$ROS2_DIR/bin/python" ] && [ "$(cat "$ROS2_STAMP" 2>/dev/null)" = "$ROS2_REQS" ] \
  && "$ROS2_DIR/bin/python" -c "$ROS2_CHECK" 2>/dev/null; then
  say "present ($ROS2_DIR)"
  exit 0
fi

# The wheels are built for CPython 3.11: Debian 12's python3 (python3.11).
PY=""
for candidate in /usr/bin/python3.11 python3.11 python3; do
  if command -v "$candidate" >/dev/null \
    && [ "$("$candidate" -c 'import sys; print("%d.%d" % sys.version_info[:2])')" = "3.11" ]; then
    PY="$(command -v "$candidate")"
    break
  fi
done
if [ -z "$PY" ] || ! "$PY" -c 'import ensurepip, venv' 2>/dev/null; then
  say "installing python3.11, python3.11-venv"
  SUDO=()
  if [ "$(id -u)" -ne 0 ]; then SUDO=(sudo -n); fi
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y -qq python3.11 python3.11-venv >/dev/null
  PY=/usr/bin/python3.11
fi

say "creating $ROS2_DIR with $ROS2_REQS ($PY)"
rm -rf "$ROS2_DIR"
mkdir -p "$(dirname "$ROS2_DIR")"
"$PY" -m venv "$ROS2_DIR"
# shellcheck disable=SC2086 # the requirements are words
"$ROS2_DIR/bin/python" -m pip install --quiet --disable-pip-version-check --no-input $ROS2_REQS
"$ROS2_DIR/bin/python" -c "$ROS2_CHECK"
printf '%s\n' "$ROS2_REQS" >"$ROS2_STAMP"
say "ready ($ROS2_DIR)"
